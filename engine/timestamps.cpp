#include "engine/timestamps.h"

#include "engine/device.h"

namespace sward {

GpuTimers::GpuTimers(Device& device, uint32_t maxPasses) : device_(device), maxPasses_(maxPasses) {
    // The queue's own timestampValidBits, not timestampComputeAndGraphics (which speaks for every queue family).
    require(device.timestampValidBits() > 0, "the GPU '" + device.name() +
                                                 "' cannot time GPU passes: its queue has no timestamps "
                                                 "(timestampValidBits 0)");
    require(device.properties().limits.timestampPeriod > 0.0f,
            "the GPU '" + device.name() + "' reports a timestampPeriod of 0");
    VkQueryPoolCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_TIMESTAMP,
        .queryCount = maxPasses * 2,
    };
    VK_CHECK(vkCreateQueryPool(device.handle(), &info, nullptr, &pool_));
}

GpuTimers::~GpuTimers() { vkDestroyQueryPool(device_.handle(), pool_, nullptr); }

void GpuTimers::reset(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, pool_, 0, maxPasses_ * 2);
    passes_.clear();
    open_ = false;
}

void GpuTimers::begin(VkCommandBuffer cmd, const std::string& pass) {
    require(!open_ && passes_.size() < maxPasses_, "GPU timer passes must not nest or exceed the pool size");
    // ALL_COMMANDS: the timestamp is written once all earlier work has completed, so a pass's interval
    // does not include the tail of the previous pass.
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(passes_.size() * 2));
    passes_.push_back(pass);
    open_ = true;
}

void GpuTimers::end(VkCommandBuffer cmd) {
    require(open_, "GpuTimers::end without begin");
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(passes_.size() * 2 - 1));
    open_ = false;
}

std::vector<std::pair<std::string, double>> GpuTimers::read() {
    std::vector<std::pair<std::string, double>> result;
    if (passes_.empty()) return result;
    std::vector<uint64_t> ticks(passes_.size() * 2);
    VK_CHECK(vkGetQueryPoolResults(device_.handle(), pool_, 0, uint32_t(ticks.size()), ticks.size() * 8, ticks.data(),
                                   8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    double period = device_.properties().limits.timestampPeriod; // nanoseconds per tick
    // Only the low timestampValidBits bits count (36 to 64 on current GPUs): masking the difference keeps a pass
    // that spans the counter's wrap-around right.
    const uint32_t bits = device_.timestampValidBits();
    const uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    for (size_t i = 0; i < passes_.size(); ++i)
        result.emplace_back(passes_[i], double((ticks[2 * i + 1] - ticks[2 * i]) & mask) * period * 1e-6);
    return result;
}

} // namespace sward
