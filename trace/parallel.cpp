// SPDX-License-Identifier: MIT
// parallel.cpp — ParallelRows (see parallel.h).
#include "trace/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

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
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(loop, false);
    loop(true);
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace pem::trace
