// examples/host-app: a host application that owns the Vulkan instance, device, queue, command buffer and the image it
// shows, and puts sward's meadow into that image. One command buffer of the host's records, in order: sward's frame
// (expansion, shadow map, main pass into sward's target), a copy into the host's image, and the host's own
// dynamic-rendering pass drawing its object over it; then the host reads its image back and checks that both its
// object and the meadow's grass are in it, and that its validation messenger saw nothing.
//
// usage: host-app SCENE.json   (exit 0: both visible, validation clean)
#include "host_application.h"

#include "common/half_float.h"
#include "engine/barriers.h"
#include "render/scene_gpu.h"
#include "scene/scene_input.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "triangle_frag.h"
#include "triangle_vert.h"

namespace {

constexpr uint32_t kWidth = 128, kHeight = 96;
constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT; // sward's HDR colour format, so a copy is enough

// The host's own image and the buffer it reads it back through (plain Vulkan, nothing of sward's).
struct HostImage {
    VkDevice device = VK_NULL_HANDLE;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory imageMemory = VK_NULL_HANDLE, bufferMemory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    ~HostImage() {
        vkDestroyImageView(device, view, nullptr);
        vkDestroyImage(device, image, nullptr);
        vkDestroyBuffer(device, buffer, nullptr);
        vkFreeMemory(device, imageMemory, nullptr);
        vkFreeMemory(device, bufferMemory, nullptr);
    }
};

VkDeviceMemory allocate(const host::HostApplication& app, VkMemoryRequirements needs, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(app.physical, &props);
    uint32_t type = 0;
    while (type < props.memoryTypeCount &&
           !((needs.memoryTypeBits >> type & 1u) && (props.memoryTypes[type].propertyFlags & flags) == flags))
        ++type;
    VkMemoryAllocateInfo info{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = needs.size,
                              .memoryTypeIndex = type};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    host::check(vkAllocateMemory(app.device, &info, nullptr, &memory));
    return memory;
}

void createHostImage(const host::HostApplication& app, HostImage& out) {
    out.device = app.device;
    VkImageCreateInfo image{.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = kFormat, .extent = {kWidth, kHeight, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT};
    host::check(vkCreateImage(app.device, &image, nullptr, &out.image));
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(app.device, out.image, &needs);
    out.imageMemory = allocate(app, needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    host::check(vkBindImageMemory(app.device, out.image, out.imageMemory, 0));
    VkImageViewCreateInfo view{.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out.image,
                               .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = kFormat,
                               .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    host::check(vkCreateImageView(app.device, &view, nullptr, &out.view));
    VkBufferCreateInfo buffer{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = uint64_t(kWidth) * kHeight * 8,
                              .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    host::check(vkCreateBuffer(app.device, &buffer, nullptr, &out.buffer));
    vkGetBufferMemoryRequirements(app.device, out.buffer, &needs);
    out.bufferMemory =
        allocate(app, needs, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    host::check(vkBindBufferMemory(app.device, out.buffer, out.bufferMemory, 0));
    host::check(vkMapMemory(app.device, out.bufferMemory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
}

// The host's pipeline: its triangle, dynamic rendering into its RGBA16F image, no depth.
struct HostPipeline {
    VkDevice device = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    ~HostPipeline() {
        vkDestroyPipeline(device, pipeline, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
    }
};

VkShaderModule shaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo info{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes, .pCode = code};
    VkShaderModule module = VK_NULL_HANDLE;
    host::check(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

void createHostPipeline(VkDevice device, HostPipeline& out) {
    out.device = device;
    VkPipelineLayoutCreateInfo layout{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    host::check(vkCreatePipelineLayout(device, &layout, nullptr, &out.layout));
    VkShaderModule vs = shaderModule(device, kTriangle_vert, sizeof(kTriangle_vert));
    VkShaderModule fs = shaderModule(device, kTriangle_frag, sizeof(kTriangle_frag));
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = vs, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = fs, .pName = "main"}};
    VkPipelineVertexInputStateCreateInfo input{.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
                                                    .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkViewport viewport{0, 0, float(kWidth), float(kHeight), 0, 1};
    VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
    VkPipelineViewportStateCreateInfo viewportState{.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                                    .viewportCount = 1, .pViewports = &viewport,
                                                    .scissorCount = 1, .pScissors = &scissor};
    VkPipelineRasterizationStateCreateInfo raster{.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
                                                  .cullMode = VK_CULL_MODE_NONE, .lineWidth = 1.0f};
    VkPipelineMultisampleStateCreateInfo multisample{.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
                                                     .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineColorBlendAttachmentState blend{.colorWriteMask = 0xf};
    VkPipelineColorBlendStateCreateInfo blendState{.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                                   .attachmentCount = 1, .pAttachments = &blend};
    VkPipelineRenderingCreateInfo rendering{.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
                                            .colorAttachmentCount = 1, .pColorAttachmentFormats = &kFormat};
    VkGraphicsPipelineCreateInfo info{.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, .pNext = &rendering,
                                      .stageCount = 2, .pStages = stages, .pVertexInputState = &input,
                                      .pInputAssemblyState = &assembly, .pViewportState = &viewportState,
                                      .pRasterizationState = &raster, .pMultisampleState = &multisample,
                                      .pColorBlendState = &blendState, .layout = out.layout};
    host::check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &out.pipeline));
    vkDestroyShaderModule(device, vs, nullptr);
    vkDestroyShaderModule(device, fs, nullptr);
}

// The frame, into the host's command buffer (docs/integration.md has the contract of each sward call).
void recordFrame(VkCommandBuffer cmd, sward::SceneGpu& gpu, sward::RenderTarget& target, const sward::Camera& camera,
                 const HostImage& image, const HostPipeline& pipeline) {
    gpu.renderer->record(cmd, target, nullptr, camera, 0.0, 0); // leaves output(0) in TRANSFER_SRC, ready to copy
    sward::imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                        VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageCopy region{.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                       .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .extent = {kWidth, kHeight, 1}};
    vkCmdCopyImage(cmd, target.output(0).handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    sward::imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo colour{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, .imageView = image.view,
                                     .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD, .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    VkRenderingInfo pass{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO, .renderArea = {{0, 0}, {kWidth, kHeight}},
                         .layerCount = 1, .colorAttachmentCount = 1, .pColorAttachments = &colour};
    vkCmdBeginRendering(cmd, &pass); // the host's own pass, over sward's meadow
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    sward::imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy readback{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {kWidth, kHeight, 1}};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.buffer, 1, &readback);
    sward::transferToHostBarrier(cmd);
}

// Submits the host's command buffer on the host's queue and waits (a host would pace frames its own way).
void submitAndWait(const host::HostApplication& app, VkCommandBuffer cmd) {
    VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    host::check(vkCreateFence(app.device, &fenceInfo, nullptr, &fence));
    VkSubmitInfo submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    host::check(vkQueueSubmit(app.queue, 1, &submit, fence));
    host::check(vkWaitForFences(app.device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkDestroyFence(app.device, fence, nullptr);
}

// Pixels of the host's object (its emissive red) and of grass (green above red and blue) in the read-back image.
void countPixels(const HostImage& image, size_t& object, size_t& grass) {
    const auto* half = static_cast<const uint16_t*>(image.mapped);
    object = grass = 0;
    for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
        const float r = sward::halfBitsToFloat(half[4 * i]), g = sward::halfBitsToFloat(half[4 * i + 1]),
                    b = sward::halfBitsToFloat(half[4 * i + 2]);
        object += r > 3.0f && g < 0.1f ? 1 : 0;
        grass += g > r && g > b ? 1 : 0;
    }
}

int run(const char* scenePath) {
    host::HostApplication app;
    size_t object = 0, grass = 0;
    {
        sward::Context ctx(app.handles()); // sward on the host's device: no instance or device of its own
        sward::SceneResources scene = sward::buildSceneResources(sward::loadSceneInput({.path = scenePath}));
        sward::SceneGpu gpu = sward::createSceneGpu(ctx, scene, 1, sward::SimulationMode::None);
        sward::RenderTarget target(ctx, sward::mainPassTargetDesc(kWidth, kHeight, 1));
        const sward::Camera camera = sward::sceneCamera(scene.scene, scene.terrain, kWidth, kHeight);
        HostImage image;
        createHostImage(app, image);
        HostPipeline pipeline;
        createHostPipeline(app.device, pipeline);
        VkCommandPoolCreateInfo poolInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .queueFamilyIndex = app.handles().queueFamily};
        VkCommandPool pool = VK_NULL_HANDLE;
        host::check(vkCreateCommandPool(app.device, &poolInfo, nullptr, &pool));
        VkCommandBufferAllocateInfo allocInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                              .commandPool = pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                              .commandBufferCount = 1};
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        host::check(vkAllocateCommandBuffers(app.device, &allocInfo, &cmd));
        VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        host::check(vkBeginCommandBuffer(cmd, &begin));
        recordFrame(cmd, gpu, target, camera, image, pipeline);
        host::check(vkEndCommandBuffer(cmd));
        submitAndWait(app, cmd);
        countPixels(image, object, grass);
        vkDestroyCommandPool(app.device, pool, nullptr);
        ctx.submitter.waitIdle();
    }
    std::printf("host-app: %zu pixels of the host's object, %zu of grass, %d validation message(s)\n", object, grass,
                app.messages);
    return object > 100 && grass > 100 && app.messages == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: host-app SCENE.json\n");
        return 2;
    }
    try {
        return run(argv[1]);
    } catch (const sward::Error& e) {
        std::fprintf(stderr, "host-app: error: %s\n", e.what());
        return 1;
    }
}
