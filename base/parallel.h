// SPDX-License-Identifier: MIT
// parallel.h — pemref's one parallel loop: independent items on the kept worker threads
// (worker_pool.h).
//
//   ParallelFor(height, threads, [&](int row) { ShadeRow(row); });
//   ForChunks(n, threads, [&](size_t first, size_t last) { ... });   // 8192 items a chunk
//   ForRanges(n, threads, minPerThread, [&](int64_t begin, int64_t end) { ... });
//
// Conventions: items are handed out in increasing order from an atomic counter; an item must
// write only its own slots, so the result is the same for any thread count (callers merge
// per-item data in item order afterwards). `progress(done, total)` is called on the calling
// thread only (which works too), after each item it finishes. An exception thrown by an item is
// rethrown after all threads stop (the one of the lowest item). A ParallelFor called from inside
// an item runs its items inline on that thread (no nested thread teams).
// ForChunks and ForRanges split a range into pieces that depend only on their arguments, never on
// which thread runs a piece (ForRanges: at most `threads` contiguous ranges, each at least
// minPerThread long — for blocked reductions).
// Not here: work stealing, priorities, SIMD.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

namespace pem::base {

void ParallelFor(int count, int threads, const std::function<void(int item)>& work,
                 const std::function<void(int done, int total)>& progress = {});

void ForChunks(size_t n, int threads, const std::function<void(size_t first, size_t last)>& fn);

void ForRanges(int64_t n, int threads, int64_t minPerThread,
               const std::function<void(int64_t begin, int64_t end)>& body);

}  // namespace pem::base
