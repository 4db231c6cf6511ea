// Wall-clock and process-CPU time since a start: the timer of sward's benchmarks, statistics and evaluations. Timings
// are reported, never fed back into results or written into data files.
#pragma once

#include <chrono>
#include <ctime>

namespace sward {

class Stopwatch {
public:
    Stopwatch() : wall_(std::chrono::steady_clock::now()), cpu_(std::clock()) {}

    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count(); }
    double ms() const { return seconds() * 1000.0; }
    // CPU time of the whole process since the start: every thread's, a CPU Vulkan driver's included. On 2 cores it
    // can be up to twice the wall time.
    double cpuMs() const { return double(std::clock() - cpu_) * 1000.0 / CLOCKS_PER_SEC; }

private:
    std::chrono::steady_clock::time_point wall_;
    std::clock_t cpu_;
};

} // namespace sward
