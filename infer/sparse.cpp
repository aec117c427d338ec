// SPDX-License-Identifier: MIT
// sparse.cpp — CSR construction, transpose, stacking and the row-parallel product (sparse.h).
#include "infer/sparse.h"

#include <stdexcept>

namespace pem::infer {

void CsrMatrix::AddRow(const std::vector<uint32_t>& rowCols, const std::vector<double>& rowVals) {
    col.insert(col.end(), rowCols.begin(), rowCols.end());
    val.insert(val.end(), rowVals.begin(), rowVals.end());
    rowPtr.push_back(static_cast<int64_t>(val.size()));
    ++rows;
}

CsrMatrix CsrFromRendering(const raster::RenderingMatrix& a) {
    CsrMatrix m;
    m.rows = a.rows;
    m.cols = a.cols;
    m.rowPtr = a.rowPtr;
    m.col = a.col;
    m.val = a.val;
    return m;
}

CsrMatrix Transpose(const CsrMatrix& a) {
    CsrMatrix t;
    t.rows = a.cols;
    t.cols = a.rows;
    // Count entries per column, prefix-sum, then scatter rows in increasing order.
    t.rowPtr.assign(static_cast<size_t>(a.cols) + 1, 0);
    for (uint32_t c : a.col) ++t.rowPtr[static_cast<size_t>(c) + 1];
    for (size_t j = 0; j < static_cast<size_t>(a.cols); ++j) t.rowPtr[j + 1] += t.rowPtr[j];
    t.col.resize(a.col.size());
    t.val.resize(a.val.size());
    std::vector<int64_t> next(t.rowPtr.begin(), t.rowPtr.end() - 1);
    for (int64_t r = 0; r < a.rows; ++r)
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k) {
            const size_t dst = static_cast<size_t>(next[a.col[static_cast<size_t>(k)]]++);
            t.col[dst] = static_cast<uint32_t>(r);
            t.val[dst] = a.val[static_cast<size_t>(k)];
        }
    return t;
}

void Multiply(const CsrMatrix& a, const Vector& x, Vector* y, int threads) {
    if (static_cast<int64_t>(x.size()) != a.cols) throw std::invalid_argument("Multiply: size");
    y->resize(static_cast<size_t>(a.rows));
    ParallelRanges(a.rows, threads, 2048, [&](int64_t r0, int64_t r1) {
        for (int64_t r = r0; r < r1; ++r) {
            double s = 0.0;
            const int64_t end = a.rowPtr[static_cast<size_t>(r) + 1];
            for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < end; ++k)
                s += a.val[static_cast<size_t>(k)] * x[a.col[static_cast<size_t>(k)]];
            (*y)[static_cast<size_t>(r)] = s;
        }
    });
}

CsrMatrix StackRows(const std::vector<RowBlock>& blocks) {
    CsrMatrix m;
    if (blocks.empty()) return m;
    m.cols = blocks.front().matrix->cols;
    for (const RowBlock& b : blocks) {
        const CsrMatrix& s = *b.matrix;
        if (s.cols != m.cols) throw std::invalid_argument("StackRows: column counts differ");
        if (b.rowWeight && static_cast<int64_t>(b.rowWeight->size()) != s.rows)
            throw std::invalid_argument("StackRows: row weights");
        for (int64_t r = 0; r < s.rows; ++r) {
            const double w =
                b.weight * (b.rowWeight ? (*b.rowWeight)[static_cast<size_t>(r)] : 1.0);
            for (int64_t k = s.rowPtr[static_cast<size_t>(r)];
                 k < s.rowPtr[static_cast<size_t>(r) + 1]; ++k) {
                m.col.push_back(s.col[static_cast<size_t>(k)]);
                m.val.push_back(w * s.val[static_cast<size_t>(k)]);
            }
            m.rowPtr.push_back(static_cast<int64_t>(m.val.size()));
        }
        m.rows += s.rows;
    }
    return m;
}

CsrMatrix StackColumns(const std::vector<const CsrMatrix*>& blocks) {
    CsrMatrix m;
    if (blocks.empty()) return m;
    m.rows = blocks.front()->rows;
    for (const CsrMatrix* b : blocks) {
        if (b->rows != m.rows) throw std::invalid_argument("StackColumns: row counts differ");
        m.cols += b->cols;
    }
    for (int64_t r = 0; r < m.rows; ++r) {
        uint32_t base = 0;
        for (const CsrMatrix* b : blocks) {
            for (int64_t k = b->rowPtr[static_cast<size_t>(r)];
                 k < b->rowPtr[static_cast<size_t>(r) + 1]; ++k) {
                m.col.push_back(base + b->col[static_cast<size_t>(k)]);
                m.val.push_back(b->val[static_cast<size_t>(k)]);
            }
            base += static_cast<uint32_t>(b->cols);
        }
        m.rowPtr.push_back(static_cast<int64_t>(m.val.size()));
    }
    return m;
}

Vector ColumnSquaredNorms(const CsrMatrix& transpose, int threads) {
    Vector out(static_cast<size_t>(transpose.rows), 0.0);
    ParallelRanges(transpose.rows, threads, 4096, [&](int64_t j0, int64_t j1) {
        for (int64_t j = j0; j < j1; ++j) {
            double s = 0.0;
            for (int64_t k = transpose.rowPtr[static_cast<size_t>(j)];
                 k < transpose.rowPtr[static_cast<size_t>(j) + 1]; ++k)
                s += transpose.val[static_cast<size_t>(k)] * transpose.val[static_cast<size_t>(k)];
            out[static_cast<size_t>(j)] = s;
        }
    });
    return out;
}

bool IsChannelDiagonal(const CsrMatrix& a) {
    for (int64_t r = 0; r < a.rows; ++r)
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            if (static_cast<int64_t>(a.col[static_cast<size_t>(k)] % kChannels) != r % kChannels)
                return false;
    return true;
}

SparseOperator::SparseOperator(CsrMatrix a) : a_(std::move(a)), at_(Transpose(a_)) {}

}  // namespace pem::infer
