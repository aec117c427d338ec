// SPDX-License-Identifier: MIT
#include "viewer_tty/matrix_market.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace pem::cli {
namespace {

// Opens path.tmp.<pid>; Commit() renames it over path, the destructor removes it otherwise.
class AtomicFile {
  public:
    explicit AtomicFile(const std::string& path)
        : path_(path), tmp_(path + ".tmp." + std::to_string(getpid())) {
        f_ = std::fopen(tmp_.c_str(), "w");
        if (!f_) throw std::runtime_error(path + ": cannot open for writing");
    }
    ~AtomicFile() {
        if (f_) std::fclose(f_);
        if (!done_) std::remove(tmp_.c_str());
    }
    FILE* get() { return f_; }
    void Commit() {
        const bool ok = std::ferror(f_) == 0;
        if (std::fclose(f_) != 0 || !ok) {
            f_ = nullptr;
            throw std::runtime_error(path_ + ": write failed");
        }
        f_ = nullptr;
        if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
            throw std::runtime_error(path_ + ": cannot rename temporary file");
        done_ = true;
    }

  private:
    std::string path_, tmp_;
    FILE* f_ = nullptr;
    bool done_ = false;
};

}  // namespace

void WriteMatrixMarket(const std::string& path, const raster::RenderingMatrix& a) {
    AtomicFile out(path);
    std::fprintf(out.get(), "%%%%MatrixMarket matrix coordinate real general\n");
    std::fprintf(out.get(),
                 "%% pemref rendering matrix: row 4*(y*width+x)+channel (rows top-down), "
                 "column 4*texel+channel (raster/texel_index.h)\n");
    std::fprintf(out.get(), "%lld %lld %lld\n", static_cast<long long>(a.rows),
                 static_cast<long long>(a.cols), static_cast<long long>(a.val.size()));
    for (int64_t r = 0; r < a.rows; ++r)
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            std::fprintf(out.get(), "%lld %u %.17g\n", static_cast<long long>(r + 1),
                         a.col[static_cast<size_t>(k)] + 1u, a.val[static_cast<size_t>(k)]);
    out.Commit();
}

void WriteVectorMarket(const std::string& path, const std::vector<double>& v,
                       const std::string& comment) {
    AtomicFile out(path);
    std::fprintf(out.get(), "%%%%MatrixMarket matrix array real general\n%% %s\n%zu 1\n",
                 comment.c_str(), v.size());
    for (double x : v) std::fprintf(out.get(), "%.17g\n", x);
    out.Commit();
}

}  // namespace pem::cli
