// SPDX-License-Identifier: MIT
// matrix_market.h — the one Matrix Market writer: sparse matrices (coordinate, real, general)
// and dense vectors (array), as scipy.io.mmread and Eigen's loadMarket read them.
//
//   WriteMatrixMarket("A.mtx", MatrixView::Of(a), "rows: pixels, columns: texels");
//   WriteVectorMarket("b.mtx", b, "target per row");
//
// Conventions: 1-based indices, values printed with %.17g (doubles round-trip exactly), one
// `% comment` line when the comment is not empty; the file appears atomically
// (atomic_file.h). Not here: reading (tests read with scipy).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pem::base {

// A CSR matrix's arrays, whatever type holds them (raster's rendering matrix, infer's K).
struct MatrixView {
    int64_t rows = 0, cols = 0;
    std::span<const int64_t> rowPtr;  // rows + 1 entries
    std::span<const uint32_t> col;
    std::span<const double> val;

    template <class Csr>
    static MatrixView Of(const Csr& m) {
        return {m.rows, m.cols, m.rowPtr, m.col, m.val};
    }
};

void WriteMatrixMarket(const std::string& path, const MatrixView& m, const std::string& comment);
void WriteVectorMarket(const std::string& path, const std::vector<double>& v,
                       const std::string& comment);

}  // namespace pem::base
