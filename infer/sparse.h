// SPDX-License-Identifier: MIT
// sparse.h — the CSR matrix of infer/ and its deterministic kernels.
//
//   CsrMatrix a = CsrFromRendering(renderingMatrix);   // raster's CSR layout, copied
//   SparseOperator op(std::move(a));                   // keeps A and A^T (both CSR)
//   op.Apply(x, &y, threads);                           // y = A x, rows split across threads
//   op.ApplyTranspose(r, &g, threads);                  // g = A^T r through the transpose CSR
//
// Conventions: double values, uint32 column indices, int64 row pointers (raster's layout). Each
// output entry of a product is one row's dot product summed in column-entry order by one
// thread, so results are the same bytes for any thread count (no atomics, no reductions across
// threads). A^T is precomputed as its own CSR whose rows list entries in increasing row order.
// Quad form: when the four rows 4q + c of every pixel q have the same taps 4t + c with the same
// values (what BuildSystem makes: raster's weights do not depend on the channel, nor do the
// confidence and the regularizer rows), SparseOperator also keeps the matrix one row per quad
// and one column per texel, and its products read one (texel, value) per tap for all four
// channels: a quarter of the memory traffic, the same sums in the same order, the same bytes.
// Not here: per-channel vector arithmetic (vector_ops.h), regularizer rows (regularizer.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "infer/vector_ops.h"
#include "raster/render.h"

namespace pem::infer {

struct CsrMatrix {
    int64_t rows = 0, cols = 0;
    std::vector<int64_t> rowPtr{0};  // rows + 1 entries
    std::vector<uint32_t> col;
    std::vector<double> val;

    int64_t NonZeros() const { return static_cast<int64_t>(val.size()); }
    // Appends one row (entries in the given order).
    void AddRow(std::span<const uint32_t> rowCols, std::span<const double> rowVals);
};

// The matrix part of raster's RenderingMatrix (offset and rendered are not copied).
CsrMatrix CsrFromRendering(const raster::RenderingMatrix& a);

// The transpose; row j lists the entries of column j in increasing row order.
CsrMatrix Transpose(const CsrMatrix& a);

// y = A x (y resized to a.rows).
void Multiply(const CsrMatrix& a, const Vector& x, Vector* y, int threads);

// A block of rows for StackRows: every row r of `matrix` scaled by weight * rowWeight[r]
// (rowWeight empty = 1). Use weight = sqrt(lambda) and rowWeight = sqrt(confidence).
struct RowBlock {
    const CsrMatrix* matrix = nullptr;
    double weight = 1.0;
    const Vector* rowWeight = nullptr;
};

// [w0 W0 B0; w1 W1 B1; ...]: all blocks have the same column count.
CsrMatrix StackRows(const std::vector<RowBlock>& blocks);
// The same with the first block's matrix consumed: its storage becomes the result's (scaled in
// place, the other blocks appended), so the largest block is not copied.
CsrMatrix StackRows(CsrMatrix&& first, double weight, const Vector* rowWeight,
                    const std::vector<RowBlock>& rest);

// The quad form of StackRows(first, weight, rowWeight, rest) read straight from the blocks: the
// same matrix QuadForm would make of the stack, bit for bit, without the stack (four times the
// quad form's size) ever being formed. False when the stack has no quad form or a block's rows
// are not whole quads (then StackRows and SparseOperator(CsrMatrix) serve). Throws as StackRows.
bool StackedQuadForm(const CsrMatrix& first, double weight, const Vector* rowWeight,
                     const std::vector<RowBlock>& rest, CsrMatrix* quads);

// [B0 B1 ...]: all blocks have the same row count; columns of block k follow those of k-1.
CsrMatrix StackColumns(const std::vector<const CsrMatrix*>& blocks);

// Squared Euclidean norm of every column (from the transpose, rows in parallel).
Vector ColumnSquaredNorms(const CsrMatrix& transpose, int threads);

// True when every entry (r, c) has r % 4 == c % 4: the channels of the system decouple, which
// the per-channel solvers require.
bool IsChannelDiagonal(const CsrMatrix& a);

// The quad form of `a` (see above) when every quad of rows qualifies; false otherwise.
bool QuadForm(const CsrMatrix& a, CsrMatrix* quads);

// How many entries ahead the quad products prefetch what they will gather (x is scattered over
// more than the caches hold; the matrix streams in order). Prefetching changes no arithmetic.
inline constexpr int64_t kGatherAhead = 64;

// One row r of a quad form times x, per channel, each sum in entry order: s[c] = Σ_k val_k ·
// x[4 col_k + c] (Scaled: x[..] · scale[c]). The arrays are passed bare so that the compiler keeps
// them in registers in the products' loops.
template <bool Scaled>
inline void QuadRowSums(const int64_t* rowPtr, const uint32_t* col, const double* val, int64_t nnz,
                        int64_t r, const double* x, const Channels& scale, double s[kChannels]) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    const int64_t end = rowPtr[r + 1];
    for (int64_t k = rowPtr[r]; k < end; ++k) {
        if (k + kGatherAhead < nnz)
            __builtin_prefetch(x + size_t{kChannels} * col[k + kGatherAhead]);
        const double v = val[k];
        const double* t = x + size_t{kChannels} * col[k];
        if constexpr (Scaled) {
            s0 += v * (t[0] * scale[0]);
            s1 += v * (t[1] * scale[1]);
            s2 += v * (t[2] * scale[2]);
            s3 += v * (t[3] * scale[3]);
        } else {
            s0 += v * t[0];
            s1 += v * t[1];
            s2 += v * t[2];
            s3 += v * t[3];
        }
    }
    s[0] = s0, s[1] = s1, s[2] = s2, s[3] = s3;
}

// y = A x for A in quad form (x and y interleaved by channel, 4 entries per column / row).
void MultiplyQuads(const CsrMatrix& quads, const Vector& x, Vector* y, int threads);

// A matrix with its transpose, for the solvers: in quad form when A has one (then only the
// quad forms of A and A^T are kept: A itself, four times their size, is given back and rebuilt
// on demand by A(); the full transpose is never formed), else in CSR.
class SparseOperator {
  public:
    SparseOperator() = default;
    explicit SparseOperator(CsrMatrix a);
    // The operator of the rows x cols matrix whose quad form is `quads` (QuadForm's or
    // StackedQuadForm's): the same as SparseOperator(that matrix).
    static SparseOperator FromQuadForm(int64_t rows, int64_t cols, CsrMatrix quads);
    // A itself (expanded from the quad form when there is one: each quad entry (p, t, v) is the
    // entries (4p + c, 4t + c, v) of the four rows, as QuadForm read them).
    CsrMatrix A() const;
    int64_t NonZeros() const { return quad_ ? kChannels * q_.NonZeros() : a_.NonZeros(); }
    // Squared Euclidean norm of every column of A, summed over the rows in increasing order
    // (the same bits from the quad form as from the full transpose).
    Vector ColumnSquaredNorms(int threads) const;
    int64_t Rows() const { return rows_; }
    int64_t Cols() const { return cols_; }
    bool HasQuadForm() const { return quad_; }
    const CsrMatrix& Quads() const { return q_; }    // valid when HasQuadForm()
    const CsrMatrix& QuadsT() const { return qt_; }  // its transpose
    void Apply(const Vector& x, Vector* y, int threads) const {
        if (quad_)
            MultiplyQuads(q_, x, y, threads);
        else
            Multiply(a_, x, y, threads);
    }
    void ApplyTranspose(const Vector& y, Vector* x, int threads) const {
        if (quad_)
            MultiplyQuads(qt_, y, x, threads);
        else
            Multiply(at_, y, x, threads);
    }

  private:
    int64_t rows_ = 0, cols_ = 0;
    CsrMatrix a_, at_;  // A and A^T, kept only without a quad form
    bool quad_ = false;
    CsrMatrix q_, qt_;  // quad forms of A and A^T
};

}  // namespace pem::infer
