// SPDX-License-Identifier: MIT
// sparse_test.cpp — infer's CSR kernels: products against a dense reference, the transpose,
// weighted stacking, column norms, and thread-count independence of products and reductions.
#include "infer/sparse.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace pem::infer {
namespace {

// A random sparse matrix (about `perRow` entries per row) and its dense copy.
struct Random {
    uint64_t s;
    double Next() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    }
};

CsrMatrix RandomMatrix(int64_t rows, int64_t cols, int perRow, uint64_t seed,
                       std::vector<double>* dense) {
    Random rng{seed};
    CsrMatrix m;
    m.cols = cols;
    dense->assign(static_cast<size_t>(rows * cols), 0.0);
    for (int64_t r = 0; r < rows; ++r) {
        std::vector<uint32_t> cs;
        std::vector<double> vs;
        for (int k = 0; k < perRow; ++k) {
            const uint32_t c = static_cast<uint32_t>(rng.Next() * static_cast<double>(cols));
            const double v = rng.Next() - 0.5;
            if (std::find(cs.begin(), cs.end(), c) != cs.end()) continue;  // no duplicates
            cs.push_back(c);
            vs.push_back(v);
            (*dense)[static_cast<size_t>(r * cols + c)] += v;
        }
        m.AddRow(cs, vs);
    }
    return m;
}

TEST(Sparse, MultiplyAndTransposeMatchDense) {
    std::vector<double> dense;
    const CsrMatrix a = RandomMatrix(37, 23, 5, 7, &dense);
    Vector x(23), y(37);
    Random rng{3};
    for (double& v : x) v = rng.Next();
    for (double& v : y) v = rng.Next();
    SparseOperator op(a);
    Vector ax, aty;
    op.Apply(x, &ax, 1);
    op.ApplyTranspose(y, &aty, 1);
    for (int64_t r = 0; r < 37; ++r) {
        double s = 0;
        for (int64_t c = 0; c < 23; ++c)
            s += dense[static_cast<size_t>(r * 23 + c)] * x[static_cast<size_t>(c)];
        EXPECT_NEAR(ax[static_cast<size_t>(r)], s, 1e-14);
    }
    for (int64_t c = 0; c < 23; ++c) {
        double s = 0;
        for (int64_t r = 0; r < 37; ++r)
            s += dense[static_cast<size_t>(r * 23 + c)] * y[static_cast<size_t>(r)];
        EXPECT_NEAR(aty[static_cast<size_t>(c)], s, 1e-14);
    }
    // Column norms from the transpose.
    const Vector norms = op.ColumnSquaredNorms(2);
    for (int64_t c = 0; c < 23; ++c) {
        double s = 0;
        for (int64_t r = 0; r < 37; ++r)
            s += dense[static_cast<size_t>(r * 23 + c)] * dense[static_cast<size_t>(r * 23 + c)];
        EXPECT_NEAR(norms[static_cast<size_t>(c)], s, 1e-14);
    }
}

// The four channel rows of every row of `quads` (columns 4t + c, the same values).
CsrMatrix ChannelRows(const CsrMatrix& quads) {
    CsrMatrix a;
    a.cols = kChannels * quads.cols;
    for (int64_t p = 0; p < quads.rows; ++p)
        for (uint32_t c = 0; c < kChannels; ++c) {
            std::vector<uint32_t> cs;
            std::vector<double> vs;
            for (int64_t k = quads.rowPtr[static_cast<size_t>(p)];
                 k < quads.rowPtr[static_cast<size_t>(p) + 1]; ++k) {
                cs.push_back(kChannels * quads.col[static_cast<size_t>(k)] + c);
                vs.push_back(quads.val[static_cast<size_t>(k)]);
            }
            a.AddRow(cs, vs);
        }
    return a;
}

void ExpectSameBits(const CsrMatrix& a, const CsrMatrix& b) {
    EXPECT_EQ(a.rows, b.rows);
    EXPECT_EQ(a.cols, b.cols);
    EXPECT_EQ(a.rowPtr, b.rowPtr);
    EXPECT_EQ(a.col, b.col);
    ASSERT_EQ(a.val.size(), b.val.size());
    EXPECT_EQ(std::memcmp(a.val.data(), b.val.data(), a.val.size() * sizeof(double)), 0);
}

// The quad form read from the blocks is QuadForm's of the stacked matrix bit for bit (image rows
// with a weight per row, equal within each quad, then two weighted regularizer-like blocks), its
// operator is SparseOperator's of the stack; a quad whose rows are weighted differently, or a
// block of rows that are not whole quads, has none.
TEST(Sparse, StackedQuadFormIsTheStacksQuadForm) {
    std::vector<double> dense;
    const CsrMatrix image = ChannelRows(RandomMatrix(11, 9, 4, 21, &dense));
    const CsrMatrix smooth = ChannelRows(RandomMatrix(6, 9, 2, 22, &dense));
    const CsrMatrix prior = ChannelRows(RandomMatrix(5, 9, 1, 23, &dense));
    Vector rowWeight(static_cast<size_t>(image.rows));
    Random rng{5};
    for (size_t r = 0; r < rowWeight.size(); r += kChannels)
        std::fill_n(rowWeight.begin() + static_cast<std::ptrdiff_t>(r), kChannels, rng.Next());
    const std::vector<RowBlock> rest = {{&smooth, 0.3, nullptr}, {&prior, 0.07, nullptr}};

    CsrMatrix direct, fromStack;
    ASSERT_TRUE(StackedQuadForm(image, 1.5, &rowWeight, rest, &direct));
    const CsrMatrix stack = StackRows(CsrMatrix(image), 1.5, &rowWeight, rest);
    ASSERT_TRUE(QuadForm(stack, &fromStack));
    ExpectSameBits(direct, fromStack);

    const SparseOperator a = SparseOperator::FromQuadForm(stack.rows, stack.cols, direct);
    const SparseOperator b(stack);
    ASSERT_TRUE(a.HasQuadForm() && b.HasQuadForm());
    ExpectSameBits(a.A(), stack);
    ExpectSameBits(a.QuadsT(), b.QuadsT());
    Vector x(static_cast<size_t>(stack.cols)), y(static_cast<size_t>(stack.rows)), ax, bx, aty, bty;
    for (double& v : x) v = rng.Next();
    for (double& v : y) v = rng.Next();
    a.Apply(x, &ax, 2), b.Apply(x, &bx, 2);
    a.ApplyTranspose(y, &aty, 2), b.ApplyTranspose(y, &bty, 2);
    EXPECT_EQ(ax, bx);
    EXPECT_EQ(aty, bty);

    // A quad's rows weighted differently: no quad form, neither way.
    Vector uneven = rowWeight;
    uneven[6] *= 2.0;
    EXPECT_FALSE(StackedQuadForm(image, 1.5, &uneven, rest, &direct));
    EXPECT_FALSE(QuadForm(StackRows(CsrMatrix(image), 1.5, &uneven, rest), &fromStack));
    // A block of rows that are not whole quads.
    CsrMatrix odd = smooth;
    odd.AddRow({}, {});
    odd.AddRow({}, {});
    EXPECT_FALSE(StackedQuadForm(image, 1.5, &rowWeight, {{&odd, 1.0, nullptr}}, &direct));
    // A block of another width is refused as StackRows refuses it.
    CsrMatrix narrow = smooth;
    narrow.cols -= kChannels;
    EXPECT_THROW(StackedQuadForm(image, 1.5, &rowWeight, {{&narrow, 1.0, nullptr}}, &direct),
                 std::invalid_argument);
}

// A matrix whose rows 4p + c hold the same values at columns 4t + c (the image and regularizer
// rows): the operator keeps only its quad form, gives A back whole from it, and its products
// equal the dense reference.
TEST(Sparse, QuadFormOperatorGivesBackTheMatrix) {
    std::vector<double> q;
    const CsrMatrix quads = RandomMatrix(9, 7, 3, 13, &q);
    const CsrMatrix a = ChannelRows(quads);
    std::vector<double> dense(static_cast<size_t>(a.rows * a.cols), 0.0);
    for (int64_t r = 0; r < a.rows; ++r)
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            dense[static_cast<size_t>(r * a.cols + a.col[static_cast<size_t>(k)])] =
                a.val[static_cast<size_t>(k)];
    const SparseOperator op(a);
    ASSERT_TRUE(op.HasQuadForm());
    EXPECT_EQ(op.Rows(), a.rows);
    EXPECT_EQ(op.Cols(), a.cols);
    EXPECT_EQ(op.NonZeros(), a.NonZeros());
    const CsrMatrix back = op.A();
    EXPECT_EQ(back.rows, a.rows);
    EXPECT_EQ(back.cols, a.cols);
    EXPECT_EQ(back.rowPtr, a.rowPtr);
    EXPECT_EQ(back.col, a.col);
    EXPECT_EQ(back.val, a.val);
    Vector x(static_cast<size_t>(a.cols)), ax;
    Random rng{17};
    for (double& v : x) v = rng.Next();
    op.Apply(x, &ax, 2);
    for (int64_t r = 0; r < a.rows; ++r) {
        double s = 0;
        for (int64_t c = 0; c < a.cols; ++c)
            s += dense[static_cast<size_t>(r * a.cols + c)] * x[static_cast<size_t>(c)];
        EXPECT_NEAR(ax[static_cast<size_t>(r)], s, 1e-14);
    }
}

TEST(Sparse, StackRowsAndColumns) {
    std::vector<double> d1, d2;
    const CsrMatrix a = RandomMatrix(4, 6, 2, 1, &d1), b = RandomMatrix(3, 6, 2, 2, &d2);
    const Vector w{1.0, 4.0, 9.0};
    const CsrMatrix s = StackRows({{&a, 2.0, nullptr}, {&b, 0.5, &w}});
    ASSERT_EQ(s.rows, 7);
    Vector x(6, 1.0), sx, ax, bx;
    Multiply(s, x, &sx, 1);
    Multiply(a, x, &ax, 1);
    Multiply(b, x, &bx, 1);
    for (size_t r = 0; r < 4; ++r) EXPECT_DOUBLE_EQ(sx[r], 2.0 * ax[r]);
    for (size_t r = 0; r < 3; ++r) EXPECT_NEAR(sx[4 + r], 0.5 * w[r] * bx[r], 1e-15);
    const CsrMatrix c = StackColumns({&a, &a});
    ASSERT_EQ(c.cols, 12);
    Vector x2(12, 1.0), cx;
    Multiply(c, x2, &cx, 1);
    for (size_t r = 0; r < 4; ++r) EXPECT_NEAR(cx[r], 2.0 * ax[r], 1e-15);
}

TEST(Sparse, SameBytesForAnyThreadCount) {
    CsrMatrix a;
    a.cols = 40000;
    Random gen{11};
    for (int64_t r = 0; r < 50000; ++r) {
        std::vector<uint32_t> cs;
        std::vector<double> vs;
        for (int k = 0; k < 8; ++k) {
            cs.push_back(static_cast<uint32_t>(gen.Next() * 40000.0));
            vs.push_back(gen.Next() - 0.5);
        }
        a.AddRow(cs, vs);
    }
    SparseOperator op(a);
    Vector x(40000), y(50000);
    Random rng{5};
    for (double& v : x) v = rng.Next();
    for (double& v : y) v = rng.Next();
    Vector ax1, ax2, aty1, aty2;
    op.Apply(x, &ax1, 1);
    op.Apply(x, &ax2, 2);
    op.ApplyTranspose(y, &aty1, 1);
    op.ApplyTranspose(y, &aty2, 3);
    EXPECT_EQ(0, std::memcmp(ax1.data(), ax2.data(), ax1.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(aty1.data(), aty2.data(), aty1.size() * sizeof(double)));
    const Channels d1 = Dot(ax1, y, 1), d2 = Dot(ax1, y, 2), d3 = Dot(ax1, y, 7);
    EXPECT_EQ(0, std::memcmp(d1.data(), d2.data(), sizeof d1));
    EXPECT_EQ(0, std::memcmp(d1.data(), d3.data(), sizeof d1));
}

}  // namespace
}  // namespace pem::infer
