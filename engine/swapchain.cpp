#include "engine/swapchain.h"

#include "engine/context.h"

#include <algorithm>

namespace sward {

namespace {

VkSemaphore createSemaphore(VkDevice device) {
    VkSemaphoreCreateInfo info{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore;
    VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
    return semaphore;
}

// Acquire and present may report a stale swapchain; that is a reason to recreate it, not an error.
bool staleResult(VkResult result) { return result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR; }

} // namespace

Swapchain::Swapchain(Context& ctx, VkSurfaceKHR surface, VkExtent2D windowExtent, bool vsync)
    : ctx_(ctx), surface_(surface), vsync_(vsync) {
    require(surface != VK_NULL_HANDLE, "a swapchain needs a window surface");
    for (VkSemaphore& s : acquired_) s = createSemaphore(ctx.vk());
    if (windowExtent.width > 0 && windowExtent.height > 0) create(windowExtent);
}

Swapchain::~Swapchain() {
    ctx_.submitter.waitIdle();
    vkQueueWaitIdle(ctx_.device.queue()); // presentation is queue work too
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(ctx_.vk(), swapchain_, nullptr);
    for (VkSemaphore s : acquired_) vkDestroySemaphore(ctx_.vk(), s, nullptr);
}

void Swapchain::destroyImages() {
    for (VkImageView v : views_) vkDestroyImageView(ctx_.vk(), v, nullptr);
    for (VkSemaphore s : finished_) vkDestroySemaphore(ctx_.vk(), s, nullptr);
    views_.clear();
    finished_.clear();
    images_.clear();
}

void Swapchain::create(VkExtent2D windowExtent) {
    VkPhysicalDevice physical = ctx_.device.physical();
    VkDevice device = ctx_.vk();
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface_, &caps));

    uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &count, formats.data()));
    require(!formats.empty(), "the window surface reports no formats");
    // An sRGB format lets the hardware encode, so shaders write linear values; else encode in the shader.
    VkSurfaceFormatKHR chosen = formats[0];
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM,
                            VK_FORMAT_R8G8B8A8_UNORM}) {
        auto it = std::find_if(formats.begin(), formats.end(), [&](const VkSurfaceFormatKHR& f) {
            return f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
        });
        if (it != formats.end()) {
            chosen = *it;
            break;
        }
    }
    format_ = chosen.format;
    colorSpace_ = chosen.colorSpace;
    srgb_ = format_ == VK_FORMAT_B8G8R8A8_SRGB || format_ == VK_FORMAT_R8G8B8A8_SRGB;

    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR; // always supported
    if (!vsync_) {
        VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface_, &count, nullptr));
        std::vector<VkPresentModeKHR> modes(count);
        VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface_, &count, modes.data()));
        for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes.begin(), modes.end(), m) != modes.end()) {
                mode = m;
                break;
            }
    }

    // currentExtent is 0xFFFFFFFF when the window size decides (Wayland); X11 reports the window size.
    extent_ = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : windowExtent;
    extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    uint32_t imageCount = std::max(caps.minImageCount + 1, 3u);
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
    transferSrc_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

    VkSwapchainKHR old = swapchain_;
    VkSwapchainCreateInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
        .surface = surface_,
        .minImageCount = imageCount,
        .imageFormat = format_,
        .imageColorSpace = colorSpace_,
        .imageExtent = extent_,
        .imageArrayLayers = 1,
        .imageUsage = VkImageUsageFlags(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
                      (transferSrc_ ? VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_SRC_BIT) : VkImageUsageFlags(0)),
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .preTransform = caps.currentTransform,
        .compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha),
        .presentMode = mode,
        .clipped = VK_TRUE,
        .oldSwapchain = old,
    };
    VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain_));
    destroyImages();
    if (old) vkDestroySwapchainKHR(device, old, nullptr);

    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));
    for (VkImage image : images_) {
        VkImageViewCreateInfo viewInfo{
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = image,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = format_,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
        VkImageView view;
        VK_CHECK(vkCreateImageView(device, &viewInfo, nullptr, &view));
        views_.push_back(view);
        finished_.push_back(createSemaphore(device));
    }
    stale_ = false;
    ++generation_;
}

bool Swapchain::acquire(uint64_t frame, VkExtent2D windowExtent, SwapchainImage& out) {
    const uint32_t slot = uint32_t(frame % gpu::kFramesInFlight);
    // The slot's previous submission must be complete before its acquire semaphore is used again.
    ctx_.submitter.wait(frameSerial_[slot]);
    if (windowExtent.width == 0 || windowExtent.height == 0) return false; // minimised: nothing to present

    if (!swapchain_ || stale_ || windowExtent.width != extent_.width || windowExtent.height != extent_.height) {
        // Every image may still be in use by earlier frames; recreation is rare (resize), so simply drain.
        ctx_.submitter.waitIdle();
        VK_CHECK(vkQueueWaitIdle(ctx_.device.queue()));
        create(windowExtent);
    }
    uint32_t index = 0;
    VkResult result = vkAcquireNextImageKHR(ctx_.vk(), swapchain_, UINT64_MAX, acquired_[slot], VK_NULL_HANDLE, &index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) {
        stale_ = true; // the semaphore was not signalled; try again next frame
        return false;
    }
    if (result == VK_SUBOPTIMAL_KHR) stale_ = true; // the image is usable: present it, recreate afterwards
    else VK_CHECK_RESULT(result, "vkAcquireNextImageKHR");
    out = {index, images_[index], views_[index], acquired_[slot], finished_[index]};
    return true;
}

void Swapchain::present(uint64_t frame, uint64_t serial, const SwapchainImage& image) {
    frameSerial_[frame % gpu::kFramesInFlight] = serial;
    VkPresentInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
        .waitSemaphoreCount = 1,
        .pWaitSemaphores = &image.finished,
        .swapchainCount = 1,
        .pSwapchains = &swapchain_,
        .pImageIndices = &image.index,
    };
    VkResult result = vkQueuePresentKHR(ctx_.device.queue(), &info);
    if (staleResult(result)) stale_ = true;
    else VK_CHECK_RESULT(result, "vkQueuePresentKHR");
}

} // namespace sward
