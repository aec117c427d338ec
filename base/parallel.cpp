// SPDX-License-Identifier: MIT
// parallel.cpp — ParallelFor and its range splits (parallel.h).
#include "base/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

#include "base/worker_pool.h"

namespace pem::base {
namespace {

thread_local bool tInsideItem = false;

// Marks the running thread as inside an item for its lifetime.
struct InsideItem {
    bool before = tInsideItem;
    InsideItem() { tInsideItem = true; }
    ~InsideItem() { tInsideItem = before; }
};

}  // namespace

void ParallelFor(int count, int threads, const std::function<void(int item)>& work,
                 const std::function<void(int done, int total)>& progress) {
    std::atomic<int> next{0}, done{0};
    std::mutex mutex;
    std::exception_ptr error;
    int errorItem = count;
    auto loop = [&](bool caller) {
        const InsideItem inside;
        for (int item = next++; item < count; item = next++) {
            try {
                work(item);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                if (item < errorItem) errorItem = item, error = std::current_exception();
            }
            const int finished = ++done;
            if (caller && progress) progress(finished, count);
        }
    };
    if (tInsideItem)
        loop(true);
    else
        RunOnWorkers(std::clamp(threads, 1, std::max(1, count)),
                     [&](int worker) { loop(worker == 0); });
    if (error) std::rethrow_exception(error);
}

void ForChunks(size_t n, int threads, const std::function<void(size_t first, size_t last)>& fn) {
    constexpr size_t kChunk = 8192;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    if (threads <= 1 || chunks <= 1) {
        if (n > 0) fn(0, n);
        return;
    }
    ParallelFor(static_cast<int>(chunks), threads, [&](int c) {
        const size_t first = static_cast<size_t>(c) * kChunk;
        fn(first, std::min(n, first + kChunk));
    });
}

void ForRanges(int64_t n, int threads, int64_t minPerThread,
               const std::function<void(int64_t begin, int64_t end)>& body) {
    const int64_t maxUseful = std::max<int64_t>(1, n / std::max<int64_t>(1, minPerThread));
    const int t = static_cast<int>(std::min<int64_t>(std::max(1, threads), maxUseful));
    if (t <= 1) {
        body(int64_t{0}, n);
        return;
    }
    const int64_t chunk = (n + t - 1) / t;
    ParallelFor(t, t, [&](int k) { body(std::min(n, chunk * k), std::min(n, chunk * (k + 1))); });
}

}  // namespace pem::base
