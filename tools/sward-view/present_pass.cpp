#include "present_pass.h"

#include "engine/barriers.h"
#include "engine/resources.h"
#include "engine/swapchain.h"

namespace sward {

PresentPass::PresentPass(Context& ctx) : ctx_(ctx) {
    VkSamplerCreateInfo sampler{
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_NEAREST,
        .minFilter = VK_FILTER_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
    };
    VK_CHECK(vkCreateSampler(ctx_.vk(), &sampler, nullptr, &sampler_));
}

PresentPass::~PresentPass() {
    destroyPipeline(ctx_.device, pipeline_);
    vkDestroySampler(ctx_.vk(), sampler_, nullptr);
}

void PresentPass::ensurePipeline(const Swapchain& swapchain) {
    if (format_ == swapchain.format()) return;
    ctx_.submitter.waitIdle();
    destroyPipeline(ctx_.device, pipeline_);
    pipeline_ = createGraphicsPipeline(
        ctx_.device,
        {.vertexShader = "present.vert",
         .fragmentShader = "present.frag",
         .cullMode = VK_CULL_MODE_NONE,
         .colorFormats = {swapchain.format()},
         .depthTest = false,
         .depthWrite = false,
         .specialization = {/* SRGB_TARGET= */ swapchain.srgb() ? 1u : 0u}},
        {.bindings = {layoutBinding(gpu::kPresentBindingImage, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT)},
         .pushConstantSize = sizeof(float),
         .pushConstantStages = VK_SHADER_STAGE_FRAGMENT_BIT});
    format_ = swapchain.format();
}

void PresentPass::record(VkCommandBuffer cmd, const Swapchain& swapchain, const SwapchainImage& image,
                         const Image& hdr, float exposure) {
    ensurePipeline(swapchain);
    // RenderTarget::end left the resolved image for copies; the present pass samples it instead.
    imageBarrier(cmd, hdr.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // The acquire semaphore is waited on at COLOR_ATTACHMENT_OUTPUT; this transition is chained to that wait.
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkExtent2D extent = swapchain.extent();
    VkRenderingAttachmentInfo color{
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = image.view,
        .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE, // the full-screen triangle covers every pixel
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
    };
    VkRenderingInfo rendering{
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, extent},
        .layerCount = 1,
        .colorAttachmentCount = 1,
        .pColorAttachments = &color,
    };
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    bindPipeline(cmd, pipeline_);
    pushDescriptors(ctx_.device, cmd, pipeline_, {sampledImage(gpu::kPresentBindingImage, hdr.view, sampler_)});
    pushConstants(cmd, pipeline_, exposure);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    // Back to where RenderTarget::begin of the next frame expects it (its transition waits for COPY).
    imageBarrier(cmd, hdr.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE);
}

void PresentPass::recordToPresent(VkCommandBuffer cmd, VkImage image) {
    // Presentation needs no access mask: the semaphore signal orders it after the writes.
    imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
}

} // namespace sward
