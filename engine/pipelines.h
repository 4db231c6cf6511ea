// Pipelines: SPIR-V loading, compute and graphics (dynamic rendering) pipelines, specialization constants,
// push constants and push descriptors.
//
// Each pipeline owns its layout and a single push-descriptor set layout: descriptors are recorded straight
// into the command buffer (vkCmdPushDescriptorSetKHR), so there are no pools to size and no set can ever
// be bound with a never-written binding (which crashes lavapipe).
#pragma once

#include "engine/vk_common.h"

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace sward {

class Device;

// Specialization constants with ids 0, 1, 2, ... in order. Label them at the call site:
// SpecConstants{/* GROUP_SIZE= */ 64, /* LOD_FADE= */ 1}.
struct SpecConstants {
    std::vector<uint32_t> values;
    SpecConstants() = default;
    SpecConstants(std::initializer_list<uint32_t> v) : values(v) {}
};

struct PipelineLayoutDesc {
    std::vector<VkDescriptorSetLayoutBinding> bindings; // set 0, pushed per draw/dispatch
    uint32_t pushConstantSize = 0;
    VkShaderStageFlags pushConstantStages = VK_SHADER_STAGE_ALL;
};

struct Pipeline {
    VkPipeline handle = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    VkShaderStageFlags pushConstantStages = 0;
};

struct GraphicsPipelineDesc {
    std::string vertexShader, fragmentShader; // SPIR-V names without ".spv"; no fragment shader = depth only
    std::vector<VkVertexInputBindingDescription> vertexBindings;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
    std::vector<VkFormat> colorFormats;
    std::vector<VkColorComponentFlags> colorWriteMasks; // per attachment; empty = write all
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    bool depthTest = true, depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER; // reversed Z
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool alphaToCoverage = false;
    float depthBias = 0.0f, depthBiasSlope = 0.0f; // e.g. shadow casters
    SpecConstants specialization; // applied to both stages
};

// The compiled SPIR-V of shader `name` (e.g. "terrain.vert"), empty when there is none. The modules are compiled at
// build time and embedded in sward_engine (tools/embed-spirv.py), so a program finds them wherever it and the
// library live: the build tree, an install prefix, the Python module.
std::span<const uint32_t> spirvModule(const std::string& name);
VkShaderModule loadShaderModule(VkDevice device, const std::string& name);

Pipeline createComputePipeline(Device& device, const std::string& shader, const PipelineLayoutDesc& layout,
                               const SpecConstants& specialization = {});
Pipeline createGraphicsPipeline(Device& device, const GraphicsPipelineDesc& desc, const PipelineLayoutDesc& layout);
void destroyPipeline(Device& device, Pipeline& pipeline);

// A binding of set 0 for pushDescriptors: one buffer range or one image.
struct DescriptorBinding {
    uint32_t binding;
    VkDescriptorType type;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0, range = VK_WHOLE_SIZE;
    VkImageView imageView = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    VkImageLayout imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
};
inline DescriptorBinding storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                                       VkDeviceSize range = VK_WHOLE_SIZE) {
    return {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer, offset, range};
}
inline DescriptorBinding uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                                       VkDeviceSize range = VK_WHOLE_SIZE) {
    return {binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, buffer, offset, range};
}
inline DescriptorBinding sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                      VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL) {
    return {binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, 0, 0, view, sampler, layout};
}

void bindPipeline(VkCommandBuffer cmd, const Pipeline& pipeline);
void pushDescriptors(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                     std::initializer_list<DescriptorBinding> bindings);
void pushConstants(VkCommandBuffer cmd, const Pipeline& pipeline, const void* data, uint32_t size);
// One indexed mesh (vertex buffer at binding 0, uint32 indices) with `pipeline` and its pushed descriptors.
void drawIndexedMesh(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                     std::initializer_list<DescriptorBinding> bindings, VkBuffer vertices, VkBuffer indices,
                     uint32_t indexCount);
template <typename T> void pushConstants(VkCommandBuffer cmd, const Pipeline& pipeline, const T& value) {
    pushConstants(cmd, pipeline, &value, sizeof(T));
}

// Workgroups of `groupSize` invocations that cover `invocations` (the last one partly).
constexpr uint32_t groupCount(uint32_t invocations, uint32_t groupSize) {
    return (invocations + groupSize - 1) / groupSize;
}
// Dispatches groupCount(invocations, groupSize) workgroups of the bound compute pipeline, at most
// gpu::kMaxGroupsX on x and the rest in rows of y; nothing when `invocations` is 0. The shader's linear index is
// gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * groupSize (skip those >= invocations).
void dispatchLinear(VkCommandBuffer cmd, uint32_t invocations, uint32_t groupSize);

// Layout binding shorthand: binding(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT).
inline VkDescriptorSetLayoutBinding layoutBinding(uint32_t binding, VkDescriptorType type, VkShaderStageFlags stages) {
    return {.binding = binding, .descriptorType = type, .descriptorCount = 1, .stageFlags = stages};
}

} // namespace sward
