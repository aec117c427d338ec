// SPDX-License-Identifier: MIT
// parallel.h — the tracer's one form of parallelism: disjoint image rows on a few threads.
//
// Conventions: rows are handed out in increasing order from an atomic counter; the callback
// must write only its own row's slots, so the result is the same for any thread count (the
// callers merge per-row data in row order afterwards). `progress(done, total)` is called on the
// calling thread only (which works too), after each row it finishes. An exception thrown for a
// row is rethrown after all threads stop (the one of the lowest row). The threads are raster/'s
// kept helpers (worker_pool.h), not started per call.
// Not here: work stealing, nested parallelism, SIMD.
#pragma once

#include <functional>

namespace pem::trace {

void ParallelRows(int rows, int threads, const std::function<void(int row)>& work,
                  const std::function<void(int done, int total)>& progress = {});

}  // namespace pem::trace
