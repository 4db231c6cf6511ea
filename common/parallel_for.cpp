#include "common/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

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
