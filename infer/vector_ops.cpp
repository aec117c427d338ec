// SPDX-License-Identifier: MIT
// vector_ops.cpp — blocked per-channel reductions and
// elementwise updates (vector_ops.h).
#include "infer/vector_ops.h"

#include <cstddef>

#include "base/parallel.h"

namespace pem::infer {
namespace {

// Sum f(k) per channel over [0, n): block partials in parallel, then the partials in order.
template <class Term>
Channels BlockedSum(int64_t n, int threads, const Term& term) {
    const int64_t blocks = (n + kReduceBlock - 1) / kReduceBlock;
    std::vector<Channels> partial(static_cast<size_t>(blocks), Channels{});
    base::ForRanges(blocks, threads, 4, [&](int64_t b0, int64_t b1) {
        for (int64_t b = b0; b < b1; ++b) {
            Channels s{};
            const int64_t end = std::min(n, (b + 1) * kReduceBlock);
            int64_t k = b * kReduceBlock;
            for (; k + kChannels <= end; k += kChannels)  // whole quads: channel c = lane c
                for (int c = 0; c < kChannels; ++c) s[static_cast<size_t>(c)] += term(k + c);
            for (; k < end; ++k) s[static_cast<size_t>(k % kChannels)] += term(k);
            partial[static_cast<size_t>(b)] = s;
        }
    });
    Channels total{};
    for (const Channels& s : partial)
        for (int c = 0; c < kChannels; ++c)
            total[static_cast<size_t>(c)] += s[static_cast<size_t>(c)];
    return total;
}

// f(k, c) for every entry k of [0, n) with its channel c = k % 4, quad by quad.
template <class F>
void ForEachEntry(size_t n, const F& f) {
    size_t k = 0;
    for (; k + kChannels <= n; k += kChannels)
        for (size_t c = 0; c < kChannels; ++c) f(k + c, c);
    for (; k < n; ++k) f(k, k % kChannels);
}

}  // namespace

Channels Dot(const Vector& a, const Vector& b, int threads) {
    return BlockedSum(static_cast<int64_t>(a.size()), threads, [&](int64_t k) {
        return a[static_cast<size_t>(k)] * b[static_cast<size_t>(k)];
    });
}

Channels SquaredNorm(const Vector& a, int threads) {
    return BlockedSum(static_cast<int64_t>(a.size()), threads, [&](int64_t k) {
        const double v = a[static_cast<size_t>(k)];
        return v * v;
    });
}

Channels Norm(const Vector& a, int threads) {
    return Sqrt(SquaredNorm(a, threads));
}

void Axpy(const Channels& alpha, const Vector& x, Vector* y) {
    double* yp = y->data();
    ForEachEntry(x.size(), [&](size_t k, size_t c) { yp[k] += alpha[c] * x[k]; });
}

void Xpay(const Vector& x, const Channels& alpha, Vector* y) {
    double* yp = y->data();
    ForEachEntry(x.size(), [&](size_t k, size_t c) { yp[k] = x[k] + alpha[c] * yp[k]; });
}

void Scale(const Channels& alpha, Vector* y) {
    double* yp = y->data();
    ForEachEntry(y->size(), [&](size_t k, size_t c) { yp[k] *= alpha[c]; });
}

void Hadamard(const Vector& d, const Vector& x, Vector* y) {
    y->resize(x.size());
    for (size_t k = 0; k < x.size(); ++k) (*y)[k] = d[k] * x[k];
}

}  // namespace pem::infer
