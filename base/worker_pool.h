// SPDX-License-Identifier: MIT
// worker_pool.h — run one function on several threads at once without starting threads per call:
// the helpers are kept waiting between calls (a frame makes dozens of such calls; starting a
// thread costs 20-100 µs here).
//
//   RunOnWorkers(2, [&](int w) { DrawMyBand(w); });   // w = 0 on the caller, 1 on a helper
//
// Conventions: fn(0) runs on the calling thread, fn(1) .. fn(workers - 1) on helper threads, all
// at the same time (fn may wait on a SpinBarrier of `workers`); the call returns when every fn
// has returned. One call uses the kept helpers at a time: a call made while another is running
// (nested, or from another thread) starts its own threads, as before. An exception thrown by
// any fn is rethrown after all have returned (the lowest worker's).
// Waiting: a helper between calls and a thread at a SpinBarrier spin for a short while
// (kSpinMicros) before they sleep, since waking a sleeping thread costs 50-100 µs on this kind of
// VM and a frame makes dozens of such waits, most of them short. Not here: work distribution (the
// callers hand out rows or bands), priorities.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

namespace pem::base {

void RunOnWorkers(int workers, const std::function<void(int worker)>& fn);

constexpr int kSpinMicros = 200;

// Spins until done() is true or kSpinMicros have passed; returns done().
bool SpinUntil(const std::function<bool()>& done);

// A reusable barrier of `count` threads (std::barrier's arrive_and_wait) that spins before it
// sleeps.
class SpinBarrier {
  public:
    explicit SpinBarrier(int count) : count_(count) {}
    void ArriveAndWait();

  private:
    const int count_;
    std::atomic<int> arrived_{0};
    std::atomic<uint32_t> generation_{0};
};

}  // namespace pem::base
