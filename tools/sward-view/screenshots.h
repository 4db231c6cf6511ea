// Screenshots: the viewer's image files. A key screenshot (F12 / P) reads back the frame's HDR colour and the
// truth pass's depth and writes <dir>/<scene name>-NNNN.exr, -NNNN-depth.exr and -NNNN.png (tonemapped); the
// headless capture (--frames N --screenshot FILE) copies the last presented swapchain image into a PNG. The scene
// name enters file names only through screenshotStem.
#pragma once

#include "engine/context.h"
#include "engine/render_target.h"
#include "engine/resources.h"

#include <cstdint>
#include <memory>
#include <string>

namespace sward {

struct SwapchainImage;

// The scene name as a file-name stem: characters other than [A-Za-z0-9._-] become '_', leading dots too (no
// hidden files, no "..") and it is cut to 64 characters; "" becomes "scene". A name from a scene file can then
// neither leave the screenshot folder nor hide in it.
std::string screenshotStem(const std::string& sceneName);

class Screenshots {
public:
    // Key screenshots go to folder `dir` (created when the first one is written).
    Screenshots(Context& ctx, std::string dir);
    ~Screenshots();
    Screenshots(const Screenshots&) = delete;
    Screenshots& operator=(const Screenshots&) = delete;

    // Before recording a key screenshot frame of `extent`: the truth (depth) target to render, made at this size
    // unless one exists, and readback buffers big enough for it.
    RenderTarget& prepareKeyShot(VkExtent2D extent);
    // Forgets the truth target (the next key screenshot makes one at its size). The GPU must be idle.
    void dropTruthTarget() { truth_.reset(); }
    // Copies `main`'s resolved colour and the truth target's depth into the readback buffers.
    void recordKeyShotReadback(VkCommandBuffer cmd, const RenderTarget& main);
    // After that frame's submission completed: writes the three files at `main`'s size with the next number;
    // returns the message for the panel ("wrote ...").
    std::string writeKeyShot(const RenderTarget& main, const std::string& sceneName, float exposure);

    // Before recording the captured frame (swapchains with TRANSFER_SRC only): a readback buffer for `extent`.
    void prepareSwapchainCapture(VkExtent2D extent);
    // Copies the presented image (COLOR_ATTACHMENT_OPTIMAL after the panel) into the readback buffer and leaves
    // it in PRESENT_SRC.
    void recordSwapchainCapture(VkCommandBuffer cmd, const SwapchainImage& image, VkExtent2D extent);
    // After that frame's submission completed: writes the captured image (8-bit RGBA or BGRA `format`) as RGB.
    void writeSwapchainPng(const std::string& path, VkExtent2D extent, VkFormat format);
    // The capture without TRANSFER_SRC: the same tonemap from `main`'s HDR image (what the window shows, minus
    // the panel).
    static void writeTonemappedPng(const std::string& path, const RenderTarget& main, VkExtent2D extent,
                                   float exposure);

private:
    Context& ctx_;
    std::string dir_;
    std::unique_ptr<RenderTarget> truth_;
    Buffer colorReadback_, depthReadback_, swapchainReadback_;
    uint64_t count_ = 0;
};

} // namespace sward
