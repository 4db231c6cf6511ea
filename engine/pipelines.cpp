#include "engine/pipelines.h"

#include "engine/device.h"
#include "shared/config.h"

#include <algorithm>

namespace sward {

VkShaderModule loadShaderModule(VkDevice device, const std::string& name) {
    const std::span<const uint32_t> code = spirvModule(name);
    require(!code.empty(), "no compiled shader '" + name + "' in sward_engine");
    require(code[0] == 0x07230203u, "shader '" + name + "' is not a SPIR-V module");
    VkShaderModuleCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = code.size() * 4, .pCode = code.data()};
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

namespace {

struct Specialization {
    std::vector<VkSpecializationMapEntry> entries;
    VkSpecializationInfo info{};
    explicit Specialization(const SpecConstants& constants) {
        for (uint32_t i = 0; i < constants.values.size(); ++i) entries.push_back({i, i * 4, 4});
        info = {uint32_t(entries.size()), entries.data(), constants.values.size() * 4, constants.values.data()};
    }
    const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

void createLayout(Device& device, const PipelineLayoutDesc& desc, Pipeline& pipeline) {
    // Vulkan guarantees 32 push descriptors and 128 bytes of push constants; sward's layouts stay within both, but
    // a layout that grows past a device's limit is refused by name rather than left to undefined behaviour.
    uint32_t descriptors = 0;
    for (const VkDescriptorSetLayoutBinding& b : desc.bindings) descriptors += b.descriptorCount;
    require(descriptors <= device.maxPushDescriptors(),
            "a pipeline layout of " + std::to_string(descriptors) + " descriptors: the GPU '" + device.name() +
                "' pushes at most " + std::to_string(device.maxPushDescriptors()) + " (maxPushDescriptors)");
    require(desc.pushConstantSize <= device.properties().limits.maxPushConstantsSize,
            "a pipeline layout of " + std::to_string(desc.pushConstantSize) + " bytes of push constants: the GPU '" +
                device.name() + "' allows " + std::to_string(device.properties().limits.maxPushConstantsSize) +
                " (maxPushConstantsSize)");
    VkDescriptorSetLayoutCreateInfo setInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
        .bindingCount = uint32_t(desc.bindings.size()),
        .pBindings = desc.bindings.data(),
    };
    VK_CHECK(vkCreateDescriptorSetLayout(device.handle(), &setInfo, nullptr, &pipeline.setLayout));
    VkPushConstantRange range{.stageFlags = desc.pushConstantStages, .offset = 0, .size = desc.pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &pipeline.setLayout,
        .pushConstantRangeCount = desc.pushConstantSize ? 1u : 0u,
        .pPushConstantRanges = &range,
    };
    VK_CHECK(vkCreatePipelineLayout(device.handle(), &layoutInfo, nullptr, &pipeline.layout));
    pipeline.pushConstantStages = desc.pushConstantStages;
}

} // namespace

Pipeline createComputePipeline(Device& device, const std::string& shader, const PipelineLayoutDesc& layout,
                               const SpecConstants& specialization) {
    Pipeline pipeline{.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE};
    createLayout(device, layout, pipeline);
    VkShaderModule module = loadShaderModule(device.handle(), shader);
    Specialization spec(specialization);
    VkComputePipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module,
                  .pName = "main",
                  .pSpecializationInfo = spec.get()},
        .layout = pipeline.layout,
    };
    VkResult result = vkCreateComputePipelines(device.handle(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline.handle);
    vkDestroyShaderModule(device.handle(), module, nullptr);
    VK_CHECK_RESULT(result, "vkCreateComputePipelines");
    return pipeline;
}

Pipeline createGraphicsPipeline(Device& device, const GraphicsPipelineDesc& desc, const PipelineLayoutDesc& layout) {
    Pipeline pipeline{.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS};
    createLayout(device, layout, pipeline);
    VkShaderModule vs = loadShaderModule(device.handle(), desc.vertexShader);
    // No fragment shader is valid: depth-only passes (shadow maps) need none.
    VkShaderModule fs = desc.fragmentShader.empty() ? VK_NULL_HANDLE : loadShaderModule(device.handle(), desc.fragmentShader);
    Specialization spec(desc.specialization);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vs,
         .pName = "main",
         .pSpecializationInfo = spec.get()},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = fs,
         .pName = "main",
         .pSpecializationInfo = spec.get()},
    };
    VkPipelineVertexInputStateCreateInfo vertexInput{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = uint32_t(desc.vertexBindings.size()),
        .pVertexBindingDescriptions = desc.vertexBindings.data(),
        .vertexAttributeDescriptionCount = uint32_t(desc.vertexAttributes.size()),
        .pVertexAttributeDescriptions = desc.vertexAttributes.data(),
    };
    VkPipelineInputAssemblyStateCreateInfo inputAssembly{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO, .topology = desc.topology};
    VkPipelineViewportStateCreateInfo viewport{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo raster{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = desc.cullMode,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .depthBiasEnable = desc.depthBias != 0.0f,
        .depthBiasConstantFactor = desc.depthBias,
        .depthBiasSlopeFactor = desc.depthBiasSlope,
        .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo multisample{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = desc.samples,
        .minSampleShading = 1.0f,
        .alphaToCoverageEnable = desc.alphaToCoverage,
    };
    VkPipelineDepthStencilStateCreateInfo depth{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = desc.depthTest,
        .depthWriteEnable = desc.depthWrite,
        .depthCompareOp = desc.depthCompare,
    };
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i)
        blends[i].colorWriteMask = i < desc.colorWriteMasks.size() ? desc.colorWriteMasks[i]
                                                                  : VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                                                        VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo blend{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = uint32_t(blends.size()),
        .pAttachments = blends.data(),
    };
    VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, .dynamicStateCount = 2, .pDynamicStates = dynamicStates};
    VkPipelineRenderingCreateInfo rendering{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = uint32_t(desc.colorFormats.size()),
        .pColorAttachmentFormats = desc.colorFormats.data(),
        .depthAttachmentFormat = desc.depthFormat,
    };
    VkGraphicsPipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &rendering,
        .stageCount = fs ? 2u : 1u,
        .pStages = stages,
        .pVertexInputState = &vertexInput,
        .pInputAssemblyState = &inputAssembly,
        .pViewportState = &viewport,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pDepthStencilState = &depth,
        .pColorBlendState = &blend,
        .pDynamicState = &dynamic,
        .layout = pipeline.layout,
    };
    VkResult result = vkCreateGraphicsPipelines(device.handle(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline.handle);
    vkDestroyShaderModule(device.handle(), vs, nullptr);
    if (fs) vkDestroyShaderModule(device.handle(), fs, nullptr);
    VK_CHECK_RESULT(result, "vkCreateGraphicsPipelines");
    return pipeline;
}

void destroyPipeline(Device& device, Pipeline& pipeline) {
    if (pipeline.handle) vkDestroyPipeline(device.handle(), pipeline.handle, nullptr);
    if (pipeline.layout) vkDestroyPipelineLayout(device.handle(), pipeline.layout, nullptr);
    if (pipeline.setLayout) vkDestroyDescriptorSetLayout(device.handle(), pipeline.setLayout, nullptr);
    pipeline = {};
}

void bindPipeline(VkCommandBuffer cmd, const Pipeline& pipeline) {
    vkCmdBindPipeline(cmd, pipeline.bindPoint, pipeline.handle);
}

void pushDescriptors(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                     std::initializer_list<DescriptorBinding> bindings) {
    std::vector<VkWriteDescriptorSet> writes;
    std::vector<VkDescriptorBufferInfo> buffers(bindings.size());
    std::vector<VkDescriptorImageInfo> images(bindings.size());
    size_t i = 0;
    for (const DescriptorBinding& b : bindings) {
        VkWriteDescriptorSet write{
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstBinding = b.binding,
            .descriptorCount = 1,
            .descriptorType = b.type,
        };
        if (b.buffer) {
            buffers[i] = {b.buffer, b.offset, b.range};
            write.pBufferInfo = &buffers[i];
        } else {
            images[i] = {b.sampler, b.imageView, b.imageLayout};
            write.pImageInfo = &images[i];
        }
        writes.push_back(write);
        ++i;
    }
    device.cmdPushDescriptorSet(cmd, pipeline.bindPoint, pipeline.layout, 0, uint32_t(writes.size()), writes.data());
}

void pushConstants(VkCommandBuffer cmd, const Pipeline& pipeline, const void* data, uint32_t size) {
    vkCmdPushConstants(cmd, pipeline.layout, pipeline.pushConstantStages, 0, size, data);
}

void dispatchLinear(VkCommandBuffer cmd, uint32_t invocations, uint32_t groupSize) {
    const uint32_t groups = groupCount(invocations, groupSize);
    if (groups == 0) return;
    const uint32_t groupsX = std::min(groups, gpu::kMaxGroupsX);
    vkCmdDispatch(cmd, groupsX, groupCount(groups, groupsX), 1);
}

void drawIndexedMesh(const Device& device, VkCommandBuffer cmd, const Pipeline& pipeline,
                     std::initializer_list<DescriptorBinding> bindings, VkBuffer vertices, VkBuffer indices,
                     uint32_t indexCount) {
    bindPipeline(cmd, pipeline);
    pushDescriptors(device, cmd, pipeline, bindings);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, indexCount, 1, 0, 0, 0);
}

} // namespace sward
