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
//  - ParallelRanges splits [0, n) into contiguous ranges, one per thread; bodies must write
//    disjoint outputs (elementwise updates, rows of a sparse product). The threads are
//    raster/'s kept workers (worker_pool.h; a solver makes thousands of these calls: no thread
//    start-up per call).
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

// Runs task(context, k) for k in [0, tasks) on raster::RunOnWorkers's kept threads: the calling
// thread takes k = 0, helpers the others; returns when all are done. Calls made from inside a
// task run their tasks inline.
void RunTasks(int tasks, void (*task)(const void* context, int k), const void* context);

// Runs body(begin, end) over [0, n) split into at most `threads` contiguous ranges (each at
// least minPerThread long); the calling thread takes the first range. The split depends only
// on (n, threads, minPerThread), never on which thread runs a range.
template <class Body>
void ParallelRanges(int64_t n, int threads, int64_t minPerThread, const Body& body) {
    const int64_t maxUseful = std::max<int64_t>(1, n / std::max<int64_t>(1, minPerThread));
    const int t = static_cast<int>(std::min<int64_t>(std::max(1, threads), maxUseful));
    if (t <= 1) {
        body(int64_t{0}, n);
        return;
    }
    struct Context {
        const Body* body;
        int64_t n, chunk;
    } ctx{&body, n, (n + t - 1) / t};
    RunTasks(
        t,
        [](const void* p, int k) {
            const auto* c = static_cast<const Context*>(p);
            (*c->body)(std::min(c->n, c->chunk * k), std::min(c->n, c->chunk * (k + 1)));
        },
        &ctx);
}

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
