// SPDX-License-Identifier: MIT
// matrix_market.cpp — Matrix Market files (matrix_market.h).
#include "base/matrix_market.h"

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "base/atomic_file.h"

namespace pem::base {
namespace {

using File = std::unique_ptr<FILE, int (*)(FILE*)>;

// Opens tmp, runs body on it, and reports a failed write or close.
template <class Body>
void WriteFile(const std::string& tmp, const Body& body) {
    File f(std::fopen(tmp.c_str(), "w"), &std::fclose);
    if (!f) throw std::runtime_error("cannot open for writing");
    body(f.get());
    const bool ok = std::ferror(f.get()) == 0;
    if (std::fclose(f.release()) != 0 || !ok) throw std::runtime_error("write failed");
}

void Header(FILE* f, const char* kind, const std::string& comment) {
    std::fprintf(f, "%%%%MatrixMarket matrix %s real general\n", kind);
    if (!comment.empty()) std::fprintf(f, "%% %s\n", comment.c_str());
}

}  // namespace

void WriteMatrixMarket(const std::string& path, const MatrixView& m, const std::string& comment) {
    WriteAtomically(path, [&](const std::string& tmp) {
        WriteFile(tmp, [&](FILE* f) {
            Header(f, "coordinate", comment);
            std::fprintf(f, "%lld %lld %lld\n", static_cast<long long>(m.rows),
                         static_cast<long long>(m.cols), static_cast<long long>(m.val.size()));
            for (int64_t r = 0; r < m.rows; ++r)
                for (int64_t k = m.rowPtr[static_cast<size_t>(r)];
                     k < m.rowPtr[static_cast<size_t>(r) + 1]; ++k)
                    std::fprintf(f, "%lld %u %.17g\n", static_cast<long long>(r + 1),
                                 m.col[static_cast<size_t>(k)] + 1u, m.val[static_cast<size_t>(k)]);
        });
    });
}

void WriteVectorMarket(const std::string& path, const std::vector<double>& v,
                       const std::string& comment) {
    WriteAtomically(path, [&](const std::string& tmp) {
        WriteFile(tmp, [&](FILE* f) {
            Header(f, "array", comment);
            std::fprintf(f, "%zu 1\n", v.size());
            for (double x : v) std::fprintf(f, "%.17g\n", x);
        });
    });
}

}  // namespace pem::base
