// The one parallel-for of sward's CPU passes (collision, placement): indices 0..count-1 on a fixed number of threads.
//
// Determinism contract: run() calls body(index, worker) exactly once per index. Indices are handed out from a
// shared counter (load balance: fields differ widely in cost), so which thread takes an index depends on the
// schedule; results do not, as long as the body writes only that index's own output slot and uses the worker's
// scratch (worker < threads()) for nothing that outlives the index. Callers merge the slots in index order, so
// results are bitwise the same for any thread count. An exception thrown by the body does not stop the other
// indices; once all have run, run() rethrows the one of the lowest index, so even the reported error does not
// depend on the schedule.
//
// Two phases in one run (run(firstCount, first, count, body)): every index of the first phase finishes before any
// index of the second starts, and the helpers are woken once. A thread that takes a second-phase index while the
// first phase is still running waits for it, spinning briefly: that is safe because indices are handed out in order,
// so every first-phase index it waits for is already running on another thread. If a first-phase index throws, the
// second phase is skipped and that exception is the one rethrown.
//
// Placement (Linux): each run first keeps the helpers off the CPU the caller is on, so that a helper woken after a
// sleep is not queued behind the caller (on a 2-CPU machine that made a paced 2-thread run as slow as one thread;
// docs/benchmarks.md). It changes where threads run, never what they compute.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

namespace sward {

using ParallelBody = std::function<void(uint32_t index, uint32_t worker)>;

// Alignment of per-worker scratch kept side by side in one array, when a body writes its fields often: two workers'
// fields on one cache line (or on the pair of lines an adjacent-line prefetcher fetches together) make each write
// stall the other core. Without it the collision pass's two threads took about 15 % longer.
inline constexpr size_t kWorkerScratchAlignment = 128;

// Threads to use when `requested` are asked for: requested, or every hardware thread when it is 0 (at least 1).
uint32_t resolveThreadCount(uint32_t requested);

// A persistent pool: its helper threads live as long as the object, because starting threads costs more than a
// whole collision tick that has little to do. Not thread-safe itself: one run() at a time.
class ParallelFor {
public:
    // threads >= 1: the calling thread plus threads - 1 helpers, started here.
    explicit ParallelFor(uint32_t threads);
    ~ParallelFor();
    ParallelFor(const ParallelFor&) = delete;
    ParallelFor& operator=(const ParallelFor&) = delete;

    uint32_t threads() const;
    // Runs body on every index in [0, count) (the caller is worker 0) and returns when all have finished.
    void run(uint32_t count, const ParallelBody& body);
    // Runs first on every index in [0, firstCount), then body on every index in [0, count) (above: a wake-up of the
    // helpers costs tens of microseconds, as much as a short first phase).
    void run(uint32_t firstCount, const ParallelBody& first, uint32_t count, const ParallelBody& body);

private:
    class Pool;
    std::unique_ptr<Pool> pool_; // null for one thread: everything runs on the caller
};

// One call on a pool of its own of min(resolveThreadCount(threads), count) threads, for passes that run once.
void parallelFor(uint32_t count, uint32_t threads, const ParallelBody& body);

} // namespace sward
