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

#if defined(__SSE2__)
#include <immintrin.h>
#endif

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

// One run's phases: indices [0, firstCount) of the first, then [0, count) of the second, taken in that order from
// one counter.
struct Phases {
    uint32_t firstCount = 0;
    const ParallelBody* first = nullptr;
    uint32_t count = 0;
    const ParallelBody* body = nullptr;
};

// The shared state of one run: the index counter and the first phase's progress, each on a cache line of its own
// (every index takes the one, every first-phase index and every waiting thread touch the other).
struct RunState {
    alignas(64) std::atomic<uint32_t> next{0};
    alignas(64) std::atomic<uint32_t> firstDone{0};
    std::atomic<bool> firstFailed{false};
    FirstError error;

    void reset() {
        next.store(0, std::memory_order_relaxed);
        firstDone.store(0, std::memory_order_relaxed);
        firstFailed.store(false, std::memory_order_relaxed);
    }
};

// Waits until the first phase has finished: briefly on the CPU (it is one share of a short step), then letting
// other threads run, in case the thread finishing it was descheduled.
void awaitFirstPhase(const RunState& state, uint32_t firstCount) {
    for (uint32_t spins = 0; state.firstDone.load(std::memory_order_acquire) < firstCount; ++spins) {
        if (spins < 4096) {
#if defined(__SSE2__)
            _mm_pause();
#endif
        } else {
            std::this_thread::yield();
        }
    }
}

// Takes indices from the run's counter until none is left.
void drain(RunState& state, const Phases& phases, uint32_t worker) {
    const uint32_t total = phases.firstCount + phases.count;
    for (uint32_t i; (i = state.next.fetch_add(1, std::memory_order_relaxed)) < total;) {
        const bool first = i < phases.firstCount;
        if (!first) {
            awaitFirstPhase(state, phases.firstCount);
            if (state.firstFailed.load(std::memory_order_relaxed)) continue;
        }
        try {
            if (first)
                (*phases.first)(i, worker);
            else
                (*phases.body)(i - phases.firstCount, worker);
        } catch (...) {
            state.error.keep(i);
            if (first) state.firstFailed.store(true, std::memory_order_relaxed);
        }
        if (first) state.firstDone.fetch_add(1, std::memory_order_release);
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

    void run(const Phases& phases) {
        placement_.steer(threads_);
        state_.reset();
        {
            std::lock_guard lock(mutex_);
            phases_ = phases;
            busy_ = uint32_t(threads_.size());
            ++generation_;
        }
        wake_.notify_all();
        drain(state_, phases, 0);
        {
            std::unique_lock lock(mutex_);
            done_.wait(lock, [&] { return busy_ == 0; });
            phases_ = {};
        }
        state_.error.rethrow();
    }

private:
    void loop(uint32_t worker) {
        uint64_t seen = 0;
        for (;;) {
            Phases phases;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
                if (quit_) return;
                seen = generation_;
                phases = phases_;
            }
            drain(state_, phases, worker);
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    Phases phases_;
    uint64_t generation_ = 0;
    uint32_t busy_ = 0;
    bool quit_ = false;
    RunState state_;
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
    run(0, body, count, body);
}

void ParallelFor::run(uint32_t firstCount, const ParallelBody& first, uint32_t count, const ParallelBody& body) {
    const Phases phases{firstCount, &first, count, &body};
    if (pool_) return pool_->run(phases);
    RunState state;
    drain(state, phases, 0);
    state.error.rethrow();
}

void parallelFor(uint32_t count, uint32_t threads, const ParallelBody& body) {
    ParallelFor(std::max(1u, std::min(resolveThreadCount(threads), count))).run(count, body);
}

} // namespace sward
