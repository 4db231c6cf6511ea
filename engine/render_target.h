// RenderTarget: offscreen colour attachments + depth, 1x or 4x MSAA, resolved at the end of rendering
// (dynamic rendering resolve), and read back to the host. The device never needs a window.
//
// Float colour attachments resolve by averaging (anti-aliased image). Integer attachments resolve with
// SAMPLE_ZERO: one real sample per pixel, never a blend of two surfaces. sward stores ground truth (depth
// bits, ids) in integer attachments for exactly that reason.
#pragma once

#include "engine/resources.h"

#include <vector>

namespace sward {

struct Context;

struct ColorAttachmentDesc {
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkClearColorValue clear{};
};

struct RenderTargetDesc {
    uint32_t width = 0, height = 0;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    std::vector<ColorAttachmentDesc> colors;
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    float depthClear = 0.0f; // reversed Z: 0 is the far plane
    bool sampleDepth = false; // keep depth and leave it in DEPTH_READ_ONLY_OPTIMAL for sampling (shadow maps)
};

class RenderTarget {
public:
    RenderTarget(Context& ctx, const RenderTargetDesc& desc);
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    const RenderTargetDesc& desc() const { return desc_; }
    std::vector<VkFormat> colorFormats() const;

    // Transitions the attachments, begins dynamic rendering with clears, sets viewport and scissor.
    void begin(VkCommandBuffer cmd);
    // Ends rendering (resolving MSAA) and leaves every output image in TRANSFER_SRC_OPTIMAL.
    void end(VkCommandBuffer cmd);

    // Single-sample result of colour attachment i (the resolve target with MSAA, else the attachment).
    const Image& output(uint32_t i) const { return resolved_[i] ? resolved_[i] : attachments_[i]; }
    const Image& depth() const { return depth_; }

    // Records a copy of output(i) into `dst` (tightly packed rows). Call after end().
    void recordReadback(VkCommandBuffer cmd, uint32_t i, const Buffer& dst) const;
    // Copies output(i) to the host (one submission, waits). Tightly packed rows, formatBytes() per texel.
    std::vector<uint8_t> readback(uint32_t i) const;

private:
    Context& ctx_;
    RenderTargetDesc desc_;
    std::vector<Image> attachments_; // rendered at desc.samples
    std::vector<Image> resolved_;    // single-sample resolve targets (MSAA only)
    Image depth_;
};

bool isIntegerFormat(VkFormat format);

} // namespace sward
