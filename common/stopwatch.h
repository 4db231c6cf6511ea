// Wall-clock and process-CPU time since a start: the one timer of sward's benchmarks, statistics, evaluations and
// simulation steps. Timings are reported, never fed back into results or written into data files.
#pragma once

#include <cassert>
#include <chrono>
#include <ctime>

namespace sward {

class Stopwatch {
public:
    // Wall time only: the steady clock, which Linux reads without a system call, so a timer inside a simulation tick
    // costs next to nothing.
    Stopwatch() : wall_(std::chrono::steady_clock::now()) {}

    // Also the process's CPU time, for cpuMs(): one system call at the start and one at each reading.
    static Stopwatch withCpuTime() {
        Stopwatch s;
        s.cpu_ = std::clock();
        s.hasCpu_ = true;
        return s;
    }

    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count(); }
    double ms() const { return seconds() * 1000.0; }
    // CPU time of the whole process since the start: every thread's, a CPU Vulkan driver's included. On 2 cores it
    // can be up to twice the wall time.
    double cpuMs() const {
        assert(hasCpu_ && "a Stopwatch made by withCpuTime()");
        return double(std::clock() - cpu_) * 1000.0 / CLOCKS_PER_SEC;
    }

private:
    std::chrono::steady_clock::time_point wall_;
    std::clock_t cpu_ = 0;
    bool hasCpu_ = false;
};

} // namespace sward
