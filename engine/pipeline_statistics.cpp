#include "engine/pipeline_statistics.h"

#include "engine/device.h"

namespace sward {

namespace {
// Results come in the order of the bits, lowest first (Vulkan spec, "Pipeline Statistics Queries").
constexpr VkQueryPipelineStatisticFlags kFigures = VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
                                                   VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
                                                   VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
                                                   VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
constexpr uint32_t kFigureCount = 4;
} // namespace

PipelineStatistics::PipelineStatistics(Device& device, uint32_t maxRanges) : device_(device), maxRanges_(maxRanges) {
    require(device.supportsPipelineStatistics(), "the device cannot count pipeline statistics");
    VkQueryPoolCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS,
        .queryCount = maxRanges,
        .pipelineStatistics = kFigures,
    };
    VK_CHECK(vkCreateQueryPool(device.handle(), &info, nullptr, &pool_));
}

PipelineStatistics::~PipelineStatistics() {
    vkDestroyQueryPool(device_.handle(), pool_, nullptr);
}

void PipelineStatistics::reset(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, pool_, 0, maxRanges_);
    ranges_.clear();
    open_ = false;
}

void PipelineStatistics::begin(VkCommandBuffer cmd, const std::string& name) {
    require(!open_ && ranges_.size() < maxRanges_, "statistics ranges must not nest or exceed the pool size");
    vkCmdBeginQuery(cmd, pool_, uint32_t(ranges_.size()), 0);
    ranges_.push_back(name);
    open_ = true;
}

void PipelineStatistics::end(VkCommandBuffer cmd) {
    require(open_, "PipelineStatistics::end without begin");
    vkCmdEndQuery(cmd, pool_, uint32_t(ranges_.size() - 1));
    open_ = false;
}

std::vector<std::pair<std::string, DrawStatistics>> PipelineStatistics::read() {
    std::vector<std::pair<std::string, DrawStatistics>> result;
    if (ranges_.empty()) return result;
    std::vector<uint64_t> values(ranges_.size() * kFigureCount);
    VK_CHECK(vkGetQueryPoolResults(device_.handle(), pool_, 0, uint32_t(ranges_.size()), values.size() * 8,
                                   values.data(), kFigureCount * 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 0; i < ranges_.size(); ++i) {
        const uint64_t* v = &values[i * kFigureCount];
        result.emplace_back(ranges_[i], DrawStatistics{.inputAssemblyPrimitives = v[0],
                                                       .vertexInvocations = v[1],
                                                       .clippingPrimitives = v[2],
                                                       .fragmentInvocations = v[3]});
    }
    return result;
}

} // namespace sward
