// SPDX-License-Identifier: MIT
// parallel.cpp — ParallelRows (see parallel.h).
#include "trace/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

#include "raster/worker_pool.h"

namespace pem::trace {

void ParallelRows(int rows, int threads, const std::function<void(int row)>& work,
                  const std::function<void(int done, int total)>& progress) {
    std::atomic<int> next{0}, done{0};
    std::mutex mutex;
    std::exception_ptr error;
    int errorRow = rows;
    auto loop = [&](bool caller) {
        for (int row = next++; row < rows; row = next++) {
            try {
                work(row);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                if (row < errorRow) errorRow = row, error = std::current_exception();
            }
            const int finished = ++done;
            if (caller && progress) progress(finished, rows);
        }
    };
    raster::RunOnWorkers(std::clamp(threads, 1, std::max(1, rows)),
                         [&](int worker) { loop(worker == 0); });
    if (error) std::rethrow_exception(error);
}

}  // namespace pem::trace
