// SPDX-License-Identifier: MIT
// worker_pool.cpp — kept helper threads for RunOnWorkers (worker_pool.h).
#include "base/worker_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pem::base {
namespace {

void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Helpers wait for a new generation, run the job as their worker number, and report back.
class Pool {
  public:
    // Runs fn(1..helpers) on kept helpers; the caller runs fn(0) and then waits here.
    void Run(int helpers, const std::function<void(int)>& fn,
             std::vector<std::exception_ptr>* errors) {
        std::unique_lock<std::mutex> lock(mutex_);
        while (static_cast<int>(threads_.size()) < helpers) {
            const int id = static_cast<int>(threads_.size()) + 1;
            threads_.emplace_back([this, id] { Loop(id); });
        }
        job_ = &fn;
        errors_ = errors;
        helpers_ = helpers;
        pending_ = helpers;
        generation_.fetch_add(1);
        lock.unlock();
        wake_.notify_all();
    }
    void Wait() {
        SpinUntil([this] { return pending_.load() == 0; });
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return pending_.load() == 0; });
        job_ = nullptr;
    }
    // Claims the helpers for one call; false while another call has them.
    bool Claim() { return !busy_.exchange(true); }
    void Release() { busy_ = false; }

  private:
    void Loop(int id) {
        uint64_t seen = 0;
        for (;;) {
            SpinUntil([&] { return generation_.load() != seen; });
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return generation_.load() != seen; });
            seen = generation_.load();
            if (id > helpers_) continue;  // this call needs fewer helpers
            const std::function<void(int)>* job = job_;
            std::vector<std::exception_ptr>* errors = errors_;
            lock.unlock();
            try {
                (*job)(id);
            } catch (...) {
                (*errors)[static_cast<size_t>(id)] = std::current_exception();
            }
            lock.lock();
            if (pending_.fetch_sub(1) == 1) done_.notify_one();
        }
    }

    std::atomic<bool> busy_{false};  // a call is using the helpers
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::thread> threads_;  // never joined: they wait until the process ends
    const std::function<void(int)>* job_ = nullptr;
    std::vector<std::exception_ptr>* errors_ = nullptr;
    std::atomic<uint64_t> generation_{0};  // written under mutex_, also read spinning
    std::atomic<int> pending_{0};          // written under mutex_, also read spinning
    int helpers_ = 0;
};

Pool& ThePool() {
    static Pool* pool = new Pool;  // never destroyed: helpers may still wait at exit
    return *pool;
}

}  // namespace

bool SpinUntil(const std::function<bool()>& done) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point until = Clock::now() + std::chrono::microseconds(kSpinMicros);
    for (;;) {
        for (int i = 0; i < 64; ++i) {
            if (done()) return true;
            CpuRelax();
        }
        if (Clock::now() > until) return done();
    }
}

void SpinBarrier::ArriveAndWait() {
    const uint32_t gen = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == count_) {
        // The last to arrive resets the count before it releases the others (they arrive again
        // only after they see the new generation).
        arrived_.store(0, std::memory_order_relaxed);
        generation_.fetch_add(1, std::memory_order_release);
        generation_.notify_all();
        return;
    }
    if (SpinUntil([&] { return generation_.load(std::memory_order_acquire) != gen; })) return;
    while (generation_.load(std::memory_order_acquire) == gen)
        generation_.wait(gen, std::memory_order_acquire);
}

void RunOnWorkers(int workers, const std::function<void(int worker)>& fn) {
    std::vector<std::exception_ptr> errors(static_cast<size_t>(std::max(1, workers)));
    auto runCaller = [&] {
        try {
            fn(0);
        } catch (...) {
            errors[0] = std::current_exception();
        }
    };
    if (workers <= 1) {
        runCaller();
    } else if (Pool& pool = ThePool(); pool.Claim()) {
        pool.Run(workers - 1, fn, &errors);
        runCaller();
        pool.Wait();
        pool.Release();
    } else {
        std::vector<std::thread> threads;
        for (int w = 1; w < workers; ++w)
            threads.emplace_back([&, w] {
                try {
                    fn(w);
                } catch (...) {
                    errors[static_cast<size_t>(w)] = std::current_exception();
                }
            });
        runCaller();
        for (std::thread& t : threads) t.join();
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace pem::base
