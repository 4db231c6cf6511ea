// GPU timestamp queries per named pass: begin(cmd, "expansion") ... end(cmd), then read() after the
// submission has completed. Used by benchmarks and the viewer; costs two timestamps per pass.
#pragma once

#include "engine/vk_common.h"

#include <string>
#include <utility>
#include <vector>

namespace sward {

class Device;

class GpuTimers {
public:
    GpuTimers(Device& device, uint32_t maxPasses);
    ~GpuTimers();
    GpuTimers(const GpuTimers&) = delete;
    GpuTimers& operator=(const GpuTimers&) = delete;

    // Resets the queries; record once per command buffer before the first begin().
    void reset(VkCommandBuffer cmd);
    void begin(VkCommandBuffer cmd, const std::string& pass);
    void end(VkCommandBuffer cmd);
    // Milliseconds per pass in recording order; call after the command buffer has completed.
    std::vector<std::pair<std::string, double>> read();

private:
    Device& device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t maxPasses_;
    std::vector<std::string> passes_;
    bool open_ = false;
};

// Times the commands recorded during its lifetime as one pass of `timers`; nothing when `timers` is null.
class ScopedGpuTimer {
public:
    ScopedGpuTimer(GpuTimers* timers, VkCommandBuffer cmd, const std::string& pass) : timers_(timers), cmd_(cmd) {
        if (timers_) timers_->begin(cmd_, pass);
    }
    ~ScopedGpuTimer() {
        if (timers_) timers_->end(cmd_);
    }
    ScopedGpuTimer(const ScopedGpuTimer&) = delete;
    ScopedGpuTimer& operator=(const ScopedGpuTimer&) = delete;

private:
    GpuTimers* timers_;
    VkCommandBuffer cmd_;
};

} // namespace sward
