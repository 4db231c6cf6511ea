#include "common/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

namespace sward {

namespace {

// The first failure in index order, whichever thread saw it first.
class FirstError {
public:
    void keep(uint32_t index) {
        std::lock_guard lock(mutex_);
        if (error_ && index_ < index) return;
        index_ = index;
        error_ = std::current_exception();
    }
    void rethrow() {
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    }

private:
    std::mutex mutex_;
    uint32_t index_ = 0;
    std::exception_ptr error_;
};

// Takes indices from `next` until none is left.
void drain(std::atomic<uint32_t>& next, uint32_t count, uint32_t worker, const ParallelBody& body, FirstError& error) {
    for (uint32_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < count;) {
        try {
            body(i, worker);
        } catch (...) {
            error.keep(i);
        }
    }
}

} // namespace

uint32_t resolveThreadCount(uint32_t requested) {
    return requested != 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
}

// Keeps the helpers off the CPU the caller runs on (Linux). A helper woken after a sleep is queued on the waker's CPU
// often enough (wake-affine placement) that, on a 2-CPU machine, the caller or the helper then waits a whole time
// slice for the other: measured there with 50 indices of 20 us each after a 1-16 ms pause, the median run took
// 1,010-1,030 us instead of 530-570 us, and the helper took no index at all in 30-40 % of the runs. Only where
// the scheduler runs the threads changes, never which index a body gets or what it computes.
class HelperPlacement {
public:
#if defined(__linux__)
    void steer(std::span<std::thread> helpers) {
        cpu_set_t allowed;
        const int caller = sched_getcpu();
        if (caller < 0 || caller >= CPU_SETSIZE || sched_getaffinity(0, sizeof allowed, &allowed) != 0) return;
        if (caller == steeredFrom_ && CPU_EQUAL(&allowed, &allowed_)) return; // unchanged: no system call
        steeredFrom_ = caller;
        allowed_ = allowed;
        cpu_set_t others = allowed;
        CPU_CLR(caller, &others);
        if (CPU_COUNT(&others) == 0) return; // one CPU: nowhere else to go
        for (std::thread& helper : helpers) pthread_setaffinity_np(helper.native_handle(), sizeof others, &others);
    }

private:
    int steeredFrom_ = -1;
    cpu_set_t allowed_{};
#else
    void steer(std::span<std::thread>) {}
#endif
};

// Helper threads sleeping on a generation counter: run() bumps it and wakes them, each drains the shared index
// counter, and the last one to finish wakes the caller.
class ParallelFor::Pool {
public:
    explicit Pool(uint32_t helpers) {
        for (uint32_t i = 0; i < helpers; ++i) threads_.emplace_back([this, i] { loop(i + 1); });
    }
    ~Pool() {
        {
            std::lock_guard lock(mutex_);
            quit_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }
    uint32_t helpers() const { return uint32_t(threads_.size()); }

    void run(uint32_t count, const ParallelBody& body) {
        placement_.steer(threads_);
        next_.store(0, std::memory_order_relaxed);
        {
            std::lock_guard lock(mutex_);
            count_ = count;
            body_ = &body;
            busy_ = uint32_t(threads_.size());
            ++generation_;
        }
        wake_.notify_all();
        drain(next_, count, 0, body, error_);
        {
            std::unique_lock lock(mutex_);
            done_.wait(lock, [&] { return busy_ == 0; });
            body_ = nullptr;
        }
        error_.rethrow();
    }

private:
    void loop(uint32_t worker) {
        uint64_t seen = 0;
        for (;;) {
            const ParallelBody* body;
            uint32_t count;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
                if (quit_) return;
                seen = generation_;
                body = body_;
                count = count_;
            }
            drain(next_, count, worker, *body, error_);
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const ParallelBody* body_ = nullptr;
    uint32_t count_ = 0;
    uint64_t generation_ = 0;
    uint32_t busy_ = 0;
    bool quit_ = false;
    alignas(64) std::atomic<uint32_t> next_{0}; // taken by every index: on a cache line of its own
    FirstError error_;
    HelperPlacement placement_;
    std::vector<std::thread> threads_;
};

ParallelFor::ParallelFor(uint32_t threads) {
    assert(threads >= 1);
    if (threads > 1) pool_ = std::make_unique<Pool>(threads - 1);
}

ParallelFor::~ParallelFor() = default;

uint32_t ParallelFor::threads() const {
    return pool_ ? pool_->helpers() + 1 : 1;
}

void ParallelFor::run(uint32_t count, const ParallelBody& body) {
    if (pool_) return pool_->run(count, body);
    std::atomic<uint32_t> next{0};
    FirstError error;
    drain(next, count, 0, body, error);
    error.rethrow();
}

void parallelFor(uint32_t count, uint32_t threads, const ParallelBody& body) {
    ParallelFor(std::max(1u, std::min(resolveThreadCount(threads), count))).run(count, body);
}

} // namespace sward
