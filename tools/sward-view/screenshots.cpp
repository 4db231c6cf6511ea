#include "screenshots.h"

#include "common/error.h"
#include "engine/barriers.h"
#include "engine/swapchain.h"
#include "io/image_files.h"
#include "render/scene_renderer.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

namespace sward {

std::string screenshotStem(const std::string& sceneName) {
    constexpr size_t kMaxLength = 64;
    std::string stem = sceneName.substr(0, kMaxLength);
    for (char& c : stem)
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-'))
            c = '_';
    for (char& c : stem) {
        if (c != '.') break;
        c = '_';
    }
    return stem.empty() ? "scene" : stem;
}

Screenshots::Screenshots(Context& ctx, std::string dir) : ctx_(ctx), dir_(std::move(dir)) {}

Screenshots::~Screenshots() {
    truth_.reset();
    for (Buffer* b : {&colorReadback_, &depthReadback_, &swapchainReadback_})
        if (*b) destroyBuffer(ctx_, *b);
}

RenderTarget& Screenshots::prepareKeyShot(VkExtent2D extent) {
    if (!truth_) truth_ = std::make_unique<RenderTarget>(ctx_, truthPassTargetDesc(extent.width, extent.height));
    uint64_t pixels = uint64_t(extent.width) * extent.height;
    for (auto [buffer, bytes] : {std::pair{&colorReadback_, pixels * 8}, std::pair{&depthReadback_, pixels * 4}})
        if (!*buffer || buffer->size < bytes) {
            if (*buffer) retireBuffer(ctx_, *buffer);
            *buffer = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
        }
    return *truth_;
}

void Screenshots::recordKeyShotReadback(VkCommandBuffer cmd, const RenderTarget& main) {
    main.recordReadback(cmd, 0, colorReadback_);
    truth_->recordReadback(cmd, 0, depthReadback_);
}

std::string Screenshots::writeKeyShot(const RenderTarget& main, const std::string& sceneName, float exposure) {
    const uint32_t w = main.desc().width, h = main.desc().height;
    const uint64_t pixels = uint64_t(w) * h;
    std::vector<uint16_t> rgba(pixels * 4);
    std::vector<float> depth(pixels);
    std::memcpy(rgba.data(), colorReadback_.mapped(), pixels * 8);
    std::memcpy(depth.data(), depthReadback_.mapped(), pixels * 4); // float bits written by the truth pass
    ensureWritableDirectory(dir_);
    char number[32];
    std::snprintf(number, sizeof number, "-%04llu", (unsigned long long)count_++);
    const std::filesystem::path folder = std::filesystem::weakly_canonical(dir_);
    const std::filesystem::path file = folder / (screenshotStem(sceneName) + number);
    // The stem cannot hold a separator; this keeps it so if screenshotStem ever changes.
    require(file.parent_path() == folder, "screenshot name '" + file.string() + "' leaves --screenshot-dir");
    const std::string base = file.string();
    writeExrRgbaHalf(base + ".exr", w, h, rgba);
    writeExrDepth(base + "-depth.exr", w, h, depth);
    writePng8(base + ".png", w, h, 3, tonemapPreview(rgba, w, h, exposure));
    return "wrote " + base + ".exr, " + base + "-depth.exr, " + base + ".png";
}

void Screenshots::prepareSwapchainCapture(VkExtent2D extent) {
    uint64_t bytes = uint64_t(extent.width) * extent.height * 4;
    if (swapchainReadback_) retireBuffer(ctx_, swapchainReadback_);
    swapchainReadback_ = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
}

void Screenshots::recordSwapchainCapture(VkCommandBuffer cmd, const SwapchainImage& image, VkExtent2D extent) {
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                             .imageExtent = {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainReadback_.handle, 1,
                           &region);
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
}

void Screenshots::writeSwapchainPng(const std::string& path, VkExtent2D extent, VkFormat format) {
    const uint64_t pixels = uint64_t(extent.width) * extent.height;
    const uint8_t* src = swapchainReadback_.mapped();
    const bool bgr = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM;
    std::vector<uint8_t> rgb(pixels * 3);
    for (uint64_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = src[p * 4 + (bgr ? 2 - c : c)];
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) ensureWritableDirectory(parent.string());
    writePng8(path, extent.width, extent.height, 3, rgb);
}

void Screenshots::writeTonemappedPng(const std::string& path, const RenderTarget& main, VkExtent2D extent,
                                     float exposure) {
    std::vector<uint8_t> bytes = main.readback(0);
    std::vector<uint16_t> rgba(bytes.size() / 2);
    std::memcpy(rgba.data(), bytes.data(), bytes.size());
    writePng8(path, extent.width, extent.height, 3, tonemapPreview(rgba, extent.width, extent.height, exposure));
}

} // namespace sward
