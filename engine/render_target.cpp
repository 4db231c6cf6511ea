#include "engine/render_target.h"

#include "engine/barriers.h"
#include "engine/context.h"

namespace sward {

bool isIntegerFormat(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8_UINT:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32B32A32_UINT: return true;
    default: return false;
    }
}

RenderTarget::RenderTarget(Context& ctx, const RenderTargetDesc& desc) : ctx_(ctx), desc_(desc) {
    require(desc.samples == VK_SAMPLE_COUNT_1_BIT || desc.samples == VK_SAMPLE_COUNT_4_BIT,
            "MSAA sample count must be 1 or 4");
    // Vulkan guarantees 4 colour attachments; the truth pass with motion flow has 5 (every desktop GPU has 8).
    const uint32_t maxColors = ctx.device.properties().limits.maxColorAttachments;
    require(desc.colors.size() <= maxColors, "a pass of " + std::to_string(desc.colors.size()) +
                                                 " colour attachments: the GPU '" + ctx.device.name() + "' allows " +
                                                 std::to_string(maxColors) + " (maxColorAttachments)");
    const bool msaa = desc.samples != VK_SAMPLE_COUNT_1_BIT;
    const VkImageUsageFlags outputUsage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    for (const ColorAttachmentDesc& color : desc.colors) {
        attachments_.push_back(createImage(
            ctx, {.format = color.format,
                  .width = desc.width,
                  .height = desc.height,
                  .samples = desc.samples,
                  .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (msaa ? VkImageUsageFlags(0) : outputUsage)}));
        resolved_.push_back(msaa ? createImage(ctx, {.format = color.format,
                                                     .width = desc.width,
                                                     .height = desc.height,
                                                     .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | outputUsage})
                                 : Image{});
    }
    if (desc.depthFormat != VK_FORMAT_UNDEFINED)
        depth_ = createImage(ctx, {.format = desc.depthFormat,
                                   .width = desc.width,
                                   .height = desc.height,
                                   .samples = desc.samples,
                                   .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                            (desc.sampleDepth ? VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT) : 0u)});
}

RenderTarget::~RenderTarget() {
    for (Image& image : attachments_) retireImage(ctx_, image);
    for (Image& image : resolved_) retireImage(ctx_, image);
    retireImage(ctx_, depth_);
}

std::vector<VkFormat> RenderTarget::colorFormats() const {
    std::vector<VkFormat> formats;
    for (const ColorAttachmentDesc& color : desc_.colors) formats.push_back(color.format);
    return formats;
}

void RenderTarget::begin(VkCommandBuffer cmd) {
    // Old contents are discarded (UNDEFINED); the only hazard is a previous frame's resolve or readback copy
    // still reading/writing these images, so wait for those stages.
    const VkPipelineStageFlags2 previousUse = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
    auto toAttachment = [&](const Image& image) {
        if (!image) return;
        imageBarrier(cmd, image.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, previousUse, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    };
    for (const Image& image : attachments_) toAttachment(image);
    for (const Image& image : resolved_) toAttachment(image);
    const VkPipelineStageFlags2 depthStages =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    if (depth_)
        imageBarrier(cmd, depth_.handle, depth_.aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     depthStages | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                     depthStages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

    std::vector<VkRenderingAttachmentInfo> colors;
    for (size_t i = 0; i < attachments_.size(); ++i) {
        VkRenderingAttachmentInfo info{
            .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = attachments_[i].view,
            .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
            .storeOp = resolved_[i] ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
            .clearValue = {.color = desc_.colors[i].clear},
        };
        if (resolved_[i]) {
            info.resolveMode = isIntegerFormat(attachments_[i].format) ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT
                                                                       : VK_RESOLVE_MODE_AVERAGE_BIT;
            info.resolveImageView = resolved_[i].view;
            info.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        }
        colors.push_back(info);
    }
    VkRenderingAttachmentInfo depth{
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = depth_.view,
        .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
        .storeOp = desc_.sampleDepth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .clearValue = {.depthStencil = {desc_.depthClear, 0}},
    };
    VkRenderingInfo rendering{
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {desc_.width, desc_.height}},
        .layerCount = 1,
        .colorAttachmentCount = uint32_t(colors.size()),
        .pColorAttachments = colors.data(),
        .pDepthAttachment = depth_ ? &depth : nullptr,
    };
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport{0.0f, 0.0f, float(desc_.width), float(desc_.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {desc_.width, desc_.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void RenderTarget::end(VkCommandBuffer cmd) {
    vkCmdEndRendering(cmd);
    if (desc_.sampleDepth)
        imageBarrier(cmd, depth_.handle, depth_.aspect, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // Resolves and stores happen in COLOR_ATTACHMENT_OUTPUT; make them visible to copies and blits.
    for (uint32_t i = 0; i < attachments_.size(); ++i)
        imageBarrier(cmd, output(i).handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
}

void RenderTarget::recordReadback(VkCommandBuffer cmd, uint32_t i, const Buffer& dst) const {
    const Image& image = output(i);
    require(dst.size >= uint64_t(desc_.width) * desc_.height * formatBytes(image.format), "readback buffer too small");
    VkBufferImageCopy region{
        .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .imageExtent = {desc_.width, desc_.height, 1},
    };
    vkCmdCopyImageToBuffer(cmd, image.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle, 1, &region);
}

std::vector<uint8_t> RenderTarget::readback(uint32_t i) const {
    uint64_t size = uint64_t(desc_.width) * desc_.height * formatBytes(output(i).format);
    Buffer staging = createBuffer(ctx_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        recordReadback(cmd, i, staging);
        transferToHostBarrier(cmd);
    });
    std::vector<uint8_t> data(staging.mapped(), staging.mapped() + size);
    destroyBuffer(ctx_, staging);
    return data;
}

} // namespace sward
