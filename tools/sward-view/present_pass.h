// PresentPass: tonemaps the resolved HDR image into the acquired swapchain image (a full-screen triangle,
// exposure as a push constant), then hands the image to presentation. The pipeline follows the swapchain's
// format (SRGB_TARGET specialisation).
#pragma once

#include "engine/context.h"
#include "engine/pipelines.h"

namespace sward {

struct Image;
class Swapchain;
struct SwapchainImage;

class PresentPass {
public:
    explicit PresentPass(Context& ctx);
    ~PresentPass();
    PresentPass(const PresentPass&) = delete;
    PresentPass& operator=(const PresentPass&) = delete;

    // Draws `hdr` (left in TRANSFER_SRC by RenderTarget::end, and left so again) into `image`, which ends in
    // COLOR_ATTACHMENT_OPTIMAL (for the panel). Rebuilds the pipeline first if the swapchain format changed.
    void record(VkCommandBuffer cmd, const Swapchain& swapchain, const SwapchainImage& image, const Image& hdr,
                float exposure);
    // Transitions `image` from COLOR_ATTACHMENT_OPTIMAL to PRESENT_SRC after the colour writes.
    static void recordToPresent(VkCommandBuffer cmd, VkImage image);

private:
    void ensurePipeline(const Swapchain& swapchain);

    Context& ctx_;
    Pipeline pipeline_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

} // namespace sward
