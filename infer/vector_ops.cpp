// SPDX-License-Identifier: MIT
// vector_ops.cpp — the persistent worker pool, blocked per-channel reductions and elementwise
// updates (vector_ops.h).
#include "infer/vector_ops.h"

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>

namespace pem::infer {
namespace {

thread_local bool tInsideTask = false;

// Threads started once and kept: each RunTasks call publishes (task, context, count) as a new
// generation; workers and the caller claim task indices until none is left.
class WorkerPool {
  public:
    ~WorkerPool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : workers_) t.join();
    }

    // False when another thread is using the pool (the caller then runs the tasks inline).
    bool TryRun(int tasks, void (*task)(const void*, int), const void* context) {
        std::unique_lock<std::mutex> owner(owner_, std::try_to_lock);
        if (!owner.owns_lock()) return false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (static_cast<int>(workers_.size()) < tasks - 1)
                workers_.emplace_back([this] { WorkerLoop(); });
            task_ = task;
            context_ = context;
            tasks_ = tasks;
            next_ = 1;
            remaining_ = tasks - 1;
            ++generation_;
        }
        wake_.notify_all();
        tInsideTask = true;
        task(context, 0);
        ClaimAndRun();
        tInsideTask = false;
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return remaining_ == 0; });
        return true;
    }

  private:
    // Runs unclaimed tasks of the current generation; called with mutex_ not held.
    void ClaimAndRun() {
        std::unique_lock<std::mutex> lock(mutex_);
        while (next_ < tasks_) {
            const int k = next_++;
            void (*task)(const void*, int) = task_;
            const void* context = context_;
            lock.unlock();
            task(context, k);
            lock.lock();
            if (--remaining_ == 0) done_.notify_all();
        }
    }

    void WorkerLoop() {
        tInsideTask = true;
        uint64_t seen = 0;
        while (true) {
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
                if (stop_) return;
                seen = generation_;
            }
            ClaimAndRun();
        }
    }

    std::mutex owner_;  // one RunTasks at a time
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::thread> workers_;
    void (*task_)(const void*, int) = nullptr;
    const void* context_ = nullptr;
    int tasks_ = 0, next_ = 0, remaining_ = 0;
    uint64_t generation_ = 0;
    bool stop_ = false;
};

WorkerPool& Pool() {
    static WorkerPool pool;
    return pool;
}

// Sum f(k) per channel over [0, n): block partials in parallel, then the partials in order.
template <class Term>
Channels BlockedSum(int64_t n, int threads, const Term& term) {
    const int64_t blocks = (n + kReduceBlock - 1) / kReduceBlock;
    std::vector<Channels> partial(static_cast<size_t>(blocks), Channels{});
    ParallelRanges(blocks, threads, 4, [&](int64_t b0, int64_t b1) {
        for (int64_t b = b0; b < b1; ++b) {
            Channels s{};
            const int64_t end = std::min(n, (b + 1) * kReduceBlock);
            int64_t k = b * kReduceBlock;
            for (; k + kChannels <= end; k += kChannels)  // whole quads: channel c = lane c
                for (int c = 0; c < kChannels; ++c) s[static_cast<size_t>(c)] += term(k + c);
            for (; k < end; ++k) s[static_cast<size_t>(k % kChannels)] += term(k);
            partial[static_cast<size_t>(b)] = s;
        }
    });
    Channels total{};
    for (const Channels& s : partial)
        for (int c = 0; c < kChannels; ++c)
            total[static_cast<size_t>(c)] += s[static_cast<size_t>(c)];
    return total;
}

// f(k, c) for every entry k of [0, n) with its channel c = k % 4, quad by quad.
template <class F>
void ForEachEntry(size_t n, const F& f) {
    size_t k = 0;
    for (; k + kChannels <= n; k += kChannels)
        for (size_t c = 0; c < kChannels; ++c) f(k + c, c);
    for (; k < n; ++k) f(k, k % kChannels);
}

}  // namespace

void RunTasks(int tasks, void (*task)(const void* context, int k), const void* context) {
    if (tasks <= 1 || tInsideTask || !Pool().TryRun(tasks, task, context))
        for (int k = 0; k < tasks; ++k) task(context, k);
}

Channels Dot(const Vector& a, const Vector& b, int threads) {
    return BlockedSum(static_cast<int64_t>(a.size()), threads, [&](int64_t k) {
        return a[static_cast<size_t>(k)] * b[static_cast<size_t>(k)];
    });
}

Channels SquaredNorm(const Vector& a, int threads) {
    return BlockedSum(static_cast<int64_t>(a.size()), threads, [&](int64_t k) {
        const double v = a[static_cast<size_t>(k)];
        return v * v;
    });
}

Channels Norm(const Vector& a, int threads) {
    return Sqrt(SquaredNorm(a, threads));
}

void Axpy(const Channels& alpha, const Vector& x, Vector* y) {
    double* yp = y->data();
    ForEachEntry(x.size(), [&](size_t k, size_t c) { yp[k] += alpha[c] * x[k]; });
}

void Xpay(const Vector& x, const Channels& alpha, Vector* y) {
    double* yp = y->data();
    ForEachEntry(x.size(), [&](size_t k, size_t c) { yp[k] = x[k] + alpha[c] * yp[k]; });
}

void Scale(const Channels& alpha, Vector* y) {
    double* yp = y->data();
    ForEachEntry(y->size(), [&](size_t k, size_t c) { yp[k] *= alpha[c]; });
}

void Hadamard(const Vector& d, const Vector& x, Vector* y) {
    y->resize(x.size());
    for (size_t k = 0; k < x.size(); ++k) (*y)[k] = d[k] * x[k];
}

}  // namespace pem::infer
