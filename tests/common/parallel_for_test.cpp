// The one parallel-for: every index once, per-worker scratch, results and errors independent of the thread count.
#include "common/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <chrono>
#include <thread>
#if defined(__linux__)
#include <sched.h>
#endif
#include <stdexcept>
#include <string>
#include <vector>

using namespace sward;

namespace {

// A float result per index that depends on the order of its additions, computed in per-worker scratch (reused
// across indices, as the collision pass does) and merged in index order.
std::vector<uint32_t> floatSums(uint32_t threads, uint32_t count) {
    std::vector<std::vector<float>> scratch(threads);
    std::vector<float> slots(count);
    ParallelFor pool(threads);
    pool.run(count, [&](uint32_t i, uint32_t worker) {
        std::vector<float>& terms = scratch[worker];
        terms.clear();
        for (uint32_t k = 0; k < 1000 + i % 7 * 300; ++k) terms.push_back(1.0f / float(k + i + 1));
        float sum = 0.0f;
        for (float t : terms) sum += t;
        slots[i] = sum;
    });
    std::vector<uint32_t> bits;
    float total = 0.0f;
    for (float s : slots) {
        total += s;
        bits.push_back(std::bit_cast<uint32_t>(s));
    }
    bits.push_back(std::bit_cast<uint32_t>(total));
    return bits;
}

} // namespace

TEST(ParallelFor, RunsEveryIndexOnceWithWorkersBelowTheThreadCount) {
    for (uint32_t threads : {1u, 2u, 3u, 8u}) {
        ParallelFor pool(threads);
        EXPECT_EQ(pool.threads(), threads);
        for (uint32_t count : {0u, 1u, 5u, 1000u}) {
            std::vector<uint32_t> runs(count, 0), workers(count, ~0u);
            pool.run(count, [&](uint32_t i, uint32_t worker) {
                ++runs[i];
                workers[i] = worker;
            });
            for (uint32_t i = 0; i < count; ++i) {
                EXPECT_EQ(runs[i], 1u) << threads << " threads, index " << i;
                EXPECT_LT(workers[i], threads);
            }
        }
    }
}

TEST(ParallelFor, ResultsAreBitwiseTheSameForOneTwoAndThreeThreads) {
    const std::vector<uint32_t> one = floatSums(1, 200);
    EXPECT_EQ(floatSums(2, 200), one);
    EXPECT_EQ(floatSums(3, 200), one);
}

TEST(ParallelFor, RethrowsTheErrorOfTheLowestIndexAfterRunningEveryIndex) {
    for (uint32_t threads : {1u, 2u, 3u}) {
        std::vector<int> ran(100, 0);
        try {
            parallelFor(100, threads, [&](uint32_t i, uint32_t) {
                ran[i] = 1;
                if (i % 30 == 17) throw std::runtime_error("index " + std::to_string(i));
            });
            ADD_FAILURE() << "no error with " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "index 17") << threads << " threads";
        }
        EXPECT_EQ(ran, std::vector<int>(100, 1)) << threads << " threads";
    }
}

// Two phases in one run: no second-phase index may start before every first-phase index has finished (the first
// phase's indices sleep, so a second-phase index taken meanwhile would see them unfinished), and each runs once.
TEST(ParallelFor, TheSecondPhaseStartsOnlyAfterTheWholeFirstPhase) {
    for (uint32_t threads : {1u, 2u, 3u}) {
        ParallelFor pool(threads);
        for (int round = 0; round < 20; ++round) {
            std::vector<std::atomic<int>> firstRan(3), secondRan(40);
            std::atomic<int> early{0};
            pool.run(
                3,
                [&](uint32_t i, uint32_t) {
                    std::this_thread::sleep_for(std::chrono::microseconds(200 * (i + 1)));
                    ++firstRan[i];
                },
                40,
                [&](uint32_t i, uint32_t) {
                    for (const std::atomic<int>& f : firstRan) early += f.load() == 1 ? 0 : 1;
                    ++secondRan[i];
                });
            EXPECT_EQ(early.load(), 0) << threads << " threads";
            for (const std::atomic<int>& f : firstRan) EXPECT_EQ(f.load(), 1);
            for (const std::atomic<int>& r : secondRan) EXPECT_EQ(r.load(), 1);
        }
    }
}

TEST(ParallelFor, AFailedFirstPhaseSkipsTheSecondAndItsErrorIsTheOneRethrown) {
    for (uint32_t threads : {1u, 2u, 3u}) {
        ParallelFor pool(threads);
        std::atomic<int> second{0};
        try {
            pool.run(
                2,
                [](uint32_t i, uint32_t) {
                    if (i == 1) throw std::runtime_error("first phase");
                },
                10,
                [&](uint32_t, uint32_t) {
                    ++second;
                    throw std::runtime_error("second phase");
                });
            ADD_FAILURE() << "no error with " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "first phase") << threads << " threads";
        }
        EXPECT_EQ(second.load(), 0) << threads << " threads";
        // The pool runs on normally afterwards.
        std::atomic<int> ran{0};
        pool.run(5, [&](uint32_t, uint32_t) { ++ran; });
        EXPECT_EQ(ran.load(), 5);
    }
}

TEST(ParallelFor, APoolRunsManyTimesAndZeroThreadsMeansEveryCore) {
    ParallelFor pool(3);
    uint64_t total = 0;
    std::vector<uint64_t> slots(64);
    for (int round = 0; round < 200; ++round) {
        pool.run(64, [&](uint32_t i, uint32_t) { slots[i] = uint64_t(i) * uint64_t(round); });
        for (uint64_t s : slots) total += s;
    }
    EXPECT_EQ(total, uint64_t(63 * 64 / 2) * uint64_t(199 * 200 / 2));
    EXPECT_GE(resolveThreadCount(0), 1u);
    EXPECT_EQ(resolveThreadCount(5), 5u);
}

#if defined(__linux__)
// A helper woken onto the caller's CPU makes one of the two wait a time slice (docs/benchmarks.md, "Helpers kept off
// the caller's CPU"): each run first keeps the helpers off the CPU the caller runs on, within the CPUs the process
// may use, and a process bound to one CPU is left alone.
TEST(ParallelFor, HelpersRunOffTheCallersCpu) {
    cpu_set_t allowed;
    ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
    if (CPU_COUNT(&allowed) < 2) GTEST_SKIP() << "the process may use one CPU only";
    ParallelFor pool(3);
    uint32_t checked = 0;
    for (int round = 0; round < 50; ++round) {
        const int before = sched_getcpu();
        std::vector<int> helperMayUseCaller(64, -1);
        pool.run(64, [&](uint32_t i, uint32_t worker) {
            if (worker == 0) { // leaves indices to the helpers
                std::this_thread::sleep_for(std::chrono::microseconds(200));
                return;
            }
            cpu_set_t mine;
            if (sched_getaffinity(0, sizeof mine, &mine) != 0) return;
            helperMayUseCaller[i] = CPU_ISSET(before, &mine) ? 1 : 0;
            // Every CPU a helper may use is one the process may use.
            cpu_set_t outside;
            CPU_XOR(&outside, &mine, &allowed);
            CPU_AND(&outside, &outside, &mine);
            EXPECT_EQ(CPU_COUNT(&outside), 0);
        });
        if (sched_getcpu() != before) continue; // the caller moved during the run: its CPU is not known
        for (int v : helperMayUseCaller) {
            if (v < 0) continue;
            EXPECT_EQ(v, 0) << "a helper may run on the caller's CPU " << before;
            ++checked;
        }
    }
    EXPECT_GT(checked, 0u);
}

TEST(ParallelFor, AProcessBoundToOneCpuStillRunsEveryIndex) {
    cpu_set_t saved, one;
    ASSERT_EQ(sched_getaffinity(0, sizeof saved, &saved), 0);
    CPU_ZERO(&one);
    CPU_SET(sched_getcpu(), &one);
    ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
    std::vector<uint32_t> slots(100, 0);
    {
        ParallelFor pool(2);
        pool.run(100, [&](uint32_t i, uint32_t) { slots[i] += i + 1; });
    }
    ASSERT_EQ(sched_setaffinity(0, sizeof saved, &saved), 0);
    for (uint32_t i = 0; i < 100; ++i) EXPECT_EQ(slots[i], i + 1);
}
#endif
