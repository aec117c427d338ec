// SPDX-License-Identifier: MIT
// vector_ops.h — per-colour-channel vector arithmetic for infer/'s solvers, the same bytes for
// any thread count.
//
// Conventions:
//  - Vectors are double and interleaved by channel: entry k belongs to channel k % 4 (columns
//    4 * texel + c and rows 4 * pixel + c, raster/texel_index.h). Every solver runs one Krylov
//    recurrence per channel, so scalars come as `Channels` (one value per channel).
//  - Reductions (Dot, SquaredNorm) sum fixed blocks of kReduceBlock entries sequentially, then
//    the block partials in block order: the order never depends on the thread count.
//  - Parallel loops are base::ForRanges (base/parallel.h): contiguous ranges, one per thread;
//    bodies write disjoint outputs (elementwise updates, rows of a sparse product).
// Not here: sparse matrices (sparse.h), solvers (solver.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pem::infer {

using Vector = std::vector<double>;
constexpr int kChannels = 4;
using Channels = std::array<double, kChannels>;
constexpr int64_t kReduceBlock = 4096;  // a multiple of kChannels

// Per-channel reductions (deterministic blocked order).
Channels Dot(const Vector& a, const Vector& b, int threads);
Channels SquaredNorm(const Vector& a, int threads);
Channels Norm(const Vector& a, int threads);

// Elementwise updates with per-channel coefficients (k % 4 picks the coefficient).
void Axpy(const Channels& alpha, const Vector& x, Vector* y);  // y += alpha x
void Xpay(const Vector& x, const Channels& alpha, Vector* y);  // y = x + alpha y
void Scale(const Channels& alpha, Vector* y);                  // y *= alpha
void Hadamard(const Vector& d, const Vector& x, Vector* y);    // y = d .* x

// Helpers on Channels.
inline double Total(const Channels& c) {
    return c[0] + c[1] + c[2] + c[3];
}
inline Channels Sqrt(Channels c) {
    for (double& v : c) v = std::sqrt(v);
    return c;
}
// 1 / c per channel, 0 where c == 0 (a channel whose vector vanished stays zero).
inline Channels SafeInverse(Channels c) {
    for (double& v : c) v = v != 0.0 ? 1.0 / v : 0.0;
    return c;
}

}  // namespace pem::infer
