// SPDX-License-Identifier: MIT
// sparse.cpp — CSR construction, transpose, stacking and the row-parallel product (sparse.h).
#include "infer/sparse.h"

#include <stdexcept>

#include "base/parallel.h"

namespace pem::infer {

void CsrMatrix::AddRow(std::span<const uint32_t> rowCols, std::span<const double> rowVals) {
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
    base::ForRanges(a.rows, threads, 2048, [&](int64_t r0, int64_t r1) {
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
    if (blocks.empty()) return CsrMatrix{};
    const RowBlock& head = blocks.front();
    return StackRows(CsrMatrix(*head.matrix), head.weight, head.rowWeight,
                     std::vector<RowBlock>(blocks.begin() + 1, blocks.end()));
}

namespace {

// The rows and entries of a stack, its blocks checked (the same column count, one weight per
// row where given).
void StackShape(const CsrMatrix& first, const Vector* rowWeight, const std::vector<RowBlock>& rest,
                size_t* rows, size_t* entries) {
    const auto checkWeights = [](const CsrMatrix& b, const Vector* w) {
        if (w && static_cast<int64_t>(w->size()) != b.rows)
            throw std::invalid_argument("StackRows: row weights");
    };
    checkWeights(first, rowWeight);
    *rows = static_cast<size_t>(first.rows), *entries = first.col.size();
    for (const RowBlock& b : rest) {
        if (b.matrix->cols != first.cols)
            throw std::invalid_argument("StackRows: column counts differ");
        checkWeights(*b.matrix, b.rowWeight);
        *rows += static_cast<size_t>(b.matrix->rows), *entries += b.matrix->col.size();
    }
}

// Appends the quads of block b (each row r's values scaled by weight * rowWeight[r], as
// StackRows scales them) to q from quad row `row` and entry `at` on; false where QuadForm would
// refuse the stacked rows (or the block's rows are not whole quads).
bool AppendQuads(const CsrMatrix& b, double weight, const Vector* rowWeight, CsrMatrix* q,
                 size_t* row, size_t* at) {
    if (b.rows % kChannels != 0) return false;
    const auto w = [&](size_t r) { return weight * (rowWeight ? (*rowWeight)[r] : 1.0); };
    for (int64_t p = 0; p < b.rows / kChannels; ++p) {
        // Rows 4p + c: equal lengths, columns 4t + c, equal scaled values.
        const size_t r0 = static_cast<size_t>(kChannels * p);
        const int64_t b0 = b.rowPtr[r0], len = b.rowPtr[r0 + 1] - b0;
        const double w0 = w(r0);
        for (size_t c = 1; c < kChannels; ++c) {
            const int64_t bc = b.rowPtr[r0 + c];
            if (b.rowPtr[r0 + c + 1] - bc != len) return false;
            const double wc = w(r0 + c);
            for (int64_t k = 0; k < len; ++k) {
                const size_t e0 = static_cast<size_t>(b0 + k), ec = static_cast<size_t>(bc + k);
                if (b.col[ec] != b.col[e0] + c || wc * b.val[ec] != w0 * b.val[e0]) return false;
            }
        }
        if (*at + static_cast<size_t>(len) > q->col.size()) return false;
        for (int64_t k = 0; k < len; ++k) {
            const size_t e0 = static_cast<size_t>(b0 + k);
            if (b.col[e0] % kChannels != 0) return false;
            q->col[*at] = b.col[e0] / kChannels;
            q->val[(*at)++] = w0 * b.val[e0];
        }
        q->rowPtr[++*row] = static_cast<int64_t>(*at);
    }
    return true;
}

}  // namespace

bool StackedQuadForm(const CsrMatrix& first, double weight, const Vector* rowWeight,
                     const std::vector<RowBlock>& rest, CsrMatrix* quads) {
    size_t rows = 0, entries = 0;
    StackShape(first, rowWeight, rest, &rows, &entries);
    if (rows % kChannels != 0 || first.cols % kChannels != 0 || entries % kChannels != 0)
        return false;
    CsrMatrix q;
    q.rows = static_cast<int64_t>(rows / kChannels);
    q.cols = first.cols / kChannels;
    q.rowPtr.assign(static_cast<size_t>(q.rows) + 1, 0);
    q.col.resize(entries / kChannels);
    q.val.resize(entries / kChannels);
    size_t row = 0, at = 0;
    if (!AppendQuads(first, weight, rowWeight, &q, &row, &at)) return false;
    for (const RowBlock& b : rest)
        if (!AppendQuads(*b.matrix, b.weight, b.rowWeight, &q, &row, &at)) return false;
    *quads = std::move(q);
    return true;
}

CsrMatrix StackRows(CsrMatrix&& first, double weight, const Vector* rowWeight,
                    const std::vector<RowBlock>& rest) {
    size_t rows = 0, entries = 0;
    StackShape(first, rowWeight, rest, &rows, &entries);
    CsrMatrix m = std::move(first);
    // The first block scaled in place: each value by its row's weight.
    for (int64_t r = 0; r < m.rows; ++r) {
        const double w = weight * (rowWeight ? (*rowWeight)[static_cast<size_t>(r)] : 1.0);
        const auto k0 = static_cast<size_t>(m.rowPtr[static_cast<size_t>(r)]);
        const auto k1 = static_cast<size_t>(m.rowPtr[static_cast<size_t>(r) + 1]);
        for (size_t k = k0; k < k1; ++k) m.val[k] = w * m.val[k];
    }
    // The others appended, sized once: columns copied, values scaled by the row's weight.
    size_t row = static_cast<size_t>(m.rows), at = m.col.size();
    m.rowPtr.resize(rows + 1);
    m.col.resize(entries);
    m.val.resize(entries);
    for (const RowBlock& b : rest) {
        const CsrMatrix& s = *b.matrix;
        std::copy(s.col.begin(), s.col.end(), m.col.begin() + static_cast<std::ptrdiff_t>(at));
        for (int64_t r = 0; r < s.rows; ++r) {
            const double w =
                b.weight * (b.rowWeight ? (*b.rowWeight)[static_cast<size_t>(r)] : 1.0);
            const auto k0 = static_cast<size_t>(s.rowPtr[static_cast<size_t>(r)]);
            const auto k1 = static_cast<size_t>(s.rowPtr[static_cast<size_t>(r) + 1]);
            for (size_t k = k0; k < k1; ++k) m.val[at + k] = w * s.val[k];
            m.rowPtr[++row] = static_cast<int64_t>(at + k1);
        }
        at += s.col.size();
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
    base::ForRanges(transpose.rows, threads, 4096, [&](int64_t j0, int64_t j1) {
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

bool QuadForm(const CsrMatrix& a, CsrMatrix* quads) {
    return StackedQuadForm(a, 1.0, nullptr, {}, quads);  // 1.0 * v == v, bit for bit
}

void MultiplyQuads(const CsrMatrix& q, const Vector& x, Vector* y, int threads) {
    if (static_cast<int64_t>(x.size()) != kChannels * q.cols)
        throw std::invalid_argument("MultiplyQuads: size");
    y->resize(static_cast<size_t>(kChannels * q.rows));
    const double* xp = x.data();
    double* yp = y->data();
    const int64_t* rowPtr = q.rowPtr.data();
    const uint32_t* col = q.col.data();
    const double* val = q.val.data();
    const int64_t nnz = q.NonZeros();
    base::ForRanges(q.rows, threads, 512, [=](int64_t r0, int64_t r1) {
        for (int64_t r = r0; r < r1; ++r)
            QuadRowSums<false>(rowPtr, col, val, nnz, r, xp, Channels{}, yp + kChannels * r);
    });
}

SparseOperator::SparseOperator(CsrMatrix a) : rows_(a.rows), cols_(a.cols), a_(std::move(a)) {
    quad_ = QuadForm(a_, &q_);
    if (quad_) {
        a_ = CsrMatrix{};
        qt_ = Transpose(q_);
    } else {
        at_ = Transpose(a_);
    }
}

SparseOperator SparseOperator::FromQuadForm(int64_t rows, int64_t cols, CsrMatrix quads) {
    if (rows != kChannels * quads.rows || cols != kChannels * quads.cols)
        throw std::invalid_argument("SparseOperator: quad form size");
    SparseOperator op;
    op.rows_ = rows, op.cols_ = cols;
    op.quad_ = true;
    op.q_ = std::move(quads);
    op.qt_ = Transpose(op.q_);
    return op;
}

CsrMatrix SparseOperator::A() const {
    if (!quad_) return a_;
    CsrMatrix a;
    a.rows = rows_, a.cols = cols_;
    a.rowPtr.resize(static_cast<size_t>(rows_) + 1);
    a.col.resize(static_cast<size_t>(NonZeros()));
    a.val.resize(a.col.size());
    size_t at = 0;
    for (int64_t p = 0; p < q_.rows; ++p) {
        const auto k0 = static_cast<size_t>(q_.rowPtr[static_cast<size_t>(p)]);
        const auto k1 = static_cast<size_t>(q_.rowPtr[static_cast<size_t>(p) + 1]);
        for (uint32_t c = 0; c < kChannels; ++c) {
            for (size_t k = k0; k < k1; ++k) {
                a.col[at] = kChannels * q_.col[k] + c;
                a.val[at++] = q_.val[k];
            }
            a.rowPtr[static_cast<size_t>(kChannels * p + c) + 1] = static_cast<int64_t>(at);
        }
    }
    return a;
}

Vector SparseOperator::ColumnSquaredNorms(int threads) const {
    if (!quad_) return infer::ColumnSquaredNorms(at_, threads);
    // Column 4t + c of A holds quad column t's values in the same row order, for every c.
    const Vector quad = infer::ColumnSquaredNorms(qt_, threads);
    Vector out(kChannels * quad.size());
    for (size_t t = 0; t < quad.size(); ++t)
        for (size_t c = 0; c < kChannels; ++c) out[kChannels * t + c] = quad[t];
    return out;
}

}  // namespace pem::infer
