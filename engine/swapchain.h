// Swapchain: presentation to a window surface, recreated when the window is resized and skipped while it is
// minimised (zero-sized).
//
// Synchronisation per frame in flight: one "image acquired" binary semaphore (the submission waits on it at
// colour-attachment output) and the timeline serial of that frame's submission (Submitter), which acts as the
// frame's fence: before a frame slot is reused its previous serial must have completed, so its acquire
// semaphore is unsignalled and free again. "Render finished" semaphores are per swapchain *image*, not per
// frame: presentation holds one until the image is acquired again, which is the only point at which it is
// known to be free (a per-frame semaphore could still be waited on by a pending present).
#pragma once

#include "engine/vk_common.h"
#include "shared/config.h"

#include <cstdint>
#include <vector>

namespace sward {

struct Context;

struct SwapchainImage {
    uint32_t index = 0;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE; // the submission waits on this (colour attachment output)
    VkSemaphore finished = VK_NULL_HANDLE; // the submission signals this; present waits on it
};

class Swapchain {
public:

    // `surface` is owned by the device (DeviceOptions::createSurface).
    Swapchain(Context& ctx, VkSurfaceKHR surface, VkExtent2D windowExtent, bool vsync);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // Waits until frame slot `frame % gpu::kFramesInFlight` is free, recreates the swapchain if it is stale or
    // `windowExtent` (the framebuffer size) differs, and acquires the next image. Returns false when nothing
    // can be presented now (minimised window, or the surface changed during acquire): skip the frame.
    bool acquire(uint64_t frame, VkExtent2D windowExtent, SwapchainImage& out);
    // Records that frame `frame` was submitted with `serial` (its fence), then presents the image.
    void present(uint64_t frame, uint64_t serial, const SwapchainImage& image);

    VkFormat format() const { return format_; }
    bool srgb() const { return srgb_; } // the format encodes sRGB on write: shaders output linear values
    VkExtent2D extent() const { return extent_; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    VkImageView view(uint32_t i) const { return views_[i]; }
    bool supportsTransferSrc() const { return transferSrc_; }
    // Incremented on every (re)creation: owners of per-image objects (framebuffers) rebuild when it changes.
    uint64_t generation() const { return generation_; }

private:
    void create(VkExtent2D windowExtent);
    void destroyImages();

    Context& ctx_;
    VkSurfaceKHR surface_;
    bool vsync_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    bool srgb_ = false, transferSrc_ = false, stale_ = false;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> finished_;         // per swapchain image
    VkSemaphore acquired_[gpu::kFramesInFlight] = {}; // per frame in flight
    uint64_t frameSerial_[gpu::kFramesInFlight] = {};
    uint64_t generation_ = 0;
};

} // namespace sward
