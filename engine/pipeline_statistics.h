// Pipeline-statistics queries per named range of draws: begin(cmd, "main") ... end(cmd), then read() after the
// submission has completed. For benchmarks: how many fragment-shader invocations ("lanes"), vertex-shader
// invocations and primitives a pass costs. lavapipe crashes on a statistics query in a command buffer that also dispatches compute, so record
// the measured draws in a command buffer of their own.
#pragma once

#include "engine/vk_common.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sward {

class Device;

struct DrawStatistics {
    uint64_t inputAssemblyPrimitives = 0; // primitives the input assembler made (triangles drawn)
    uint64_t vertexInvocations = 0;       // vertex-shader invocations (a vertex an indexed draw reuses may count once)
    uint64_t clippingPrimitives = 0;      // primitives that left clipping (after frustum culling and clipping)
    uint64_t fragmentInvocations = 0;     // fragment-shader invocations, helper lanes included where counted
};

class PipelineStatistics {
public:
    // Requires Device::supportsPipelineStatistics().
    PipelineStatistics(Device& device, uint32_t maxRanges);
    ~PipelineStatistics();
    PipelineStatistics(const PipelineStatistics&) = delete;
    PipelineStatistics& operator=(const PipelineStatistics&) = delete;

    // Resets the queries; record once per command buffer, outside a rendering pass, before the first begin().
    void reset(VkCommandBuffer cmd);
    // Ranges must not nest (one statistics query may be active at a time).
    void begin(VkCommandBuffer cmd, const std::string& name);
    void end(VkCommandBuffer cmd);
    // Figures per range in recording order; call after the command buffer has completed.
    std::vector<std::pair<std::string, DrawStatistics>> read();

private:
    Device& device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t maxRanges_;
    std::vector<std::string> ranges_;
    bool open_ = false;
};

} // namespace sward
