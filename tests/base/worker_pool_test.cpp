// SPDX-License-Identifier: MIT
// worker_pool_test.cpp — RunOnWorkers: every worker runs exactly once and all at the same time
// (a barrier of all of them completes), calls in a row reuse the helpers, nested and concurrent
// calls still run, and exceptions reach the caller. SpinBarrier: no thread passes a phase before
// every thread has finished the previous one, with short phases (spinning) and long ones
// (sleeping).
#include "base/worker_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <barrier>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace pem::base {
namespace {

TEST(WorkerPool, EveryWorkerOnceAndConcurrently) {
    for (int workers : {1, 2, 3, 5, 2, 4}) {
        std::vector<int> ran(static_cast<size_t>(workers), 0);
        std::barrier sync(workers);  // completes only if all workers run at once
        RunOnWorkers(workers, [&](int w) {
            ++ran[static_cast<size_t>(w)];
            sync.arrive_and_wait();
        });
        EXPECT_EQ(ran, std::vector<int>(static_cast<size_t>(workers), 1)) << workers;
    }
}

TEST(WorkerPool, ManyCallsInARow) {
    std::atomic<int> total{0};
    for (int call = 0; call < 500; ++call) RunOnWorkers(3, [&](int w) { total += w + 1; });
    EXPECT_EQ(total.load(), 500 * 6);
}

TEST(WorkerPool, NestedAndConcurrentCalls) {
    std::atomic<int> inner{0};
    RunOnWorkers(2, [&](int) { RunOnWorkers(3, [&](int) { ++inner; }); });
    EXPECT_EQ(inner.load(), 6);
    std::atomic<int> count{0};
    std::thread other([&] {
        for (int k = 0; k < 50; ++k) RunOnWorkers(2, [&](int) { ++count; });
    });
    for (int k = 0; k < 50; ++k) RunOnWorkers(2, [&](int) { ++count; });
    other.join();
    EXPECT_EQ(count.load(), 200);
}

TEST(WorkerPool, SpinBarrierSeparatesPhases) {
    constexpr int kWorkers = 3, kPhases = 400;
    SpinBarrier sync(kWorkers);
    std::vector<std::atomic<int>> done(kPhases);
    std::atomic<int> early{0};
    RunOnWorkers(kWorkers, [&](int w) {
        for (int p = 0; p < kPhases; ++p) {
            // Every 50th phase, one worker is slow for longer than the spin: the others sleep.
            if (p % 50 == 0 && w == p / 50 % kWorkers)
                std::this_thread::sleep_for(std::chrono::microseconds(3 * kSpinMicros));
            ++done[static_cast<size_t>(p)];
            sync.ArriveAndWait();
            if (done[static_cast<size_t>(p)].load() != kWorkers) ++early;
        }
    });
    EXPECT_EQ(early.load(), 0);
    for (int p = 0; p < kPhases; ++p) EXPECT_EQ(done[static_cast<size_t>(p)].load(), kWorkers);
}

TEST(WorkerPool, ExceptionsReachTheCaller) {
    EXPECT_THROW(RunOnWorkers(3,
                              [](int w) {
                                  if (w == 2) throw std::runtime_error("worker 2");
                              }),
                 std::runtime_error);
    EXPECT_THROW(RunOnWorkers(1, [](int) { throw std::logic_error("caller"); }), std::logic_error);
    std::atomic<int> after{0};
    RunOnWorkers(3, [&](int) { ++after; });  // the helpers still work
    EXPECT_EQ(after.load(), 3);
}

}  // namespace
}  // namespace pem::base
