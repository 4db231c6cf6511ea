// Ui: the viewer's panel (Dear ImGui, Debian's libimgui-dev with its GLFW and Vulkan backends).
//
// ImGui 1.86's Vulkan backend draws inside a VkRenderPass (it predates dynamic rendering), so the panel gets a
// one-subpass render pass of its own that loads the tonemapped swapchain image and leaves it in
// COLOR_ATTACHMENT_OPTIMAL; the viewer then transitions it for presentation. Framebuffers follow the swapchain.
#pragma once

#include "engine/context.h"
#include "scene/scene.h"

#include <string>
#include <utility>
#include <vector>

struct GLFWwindow;

namespace sward {

class Swapchain;

// What the panel shows and edits. The viewer reads the edits back after panel().
struct PanelState {
    // Live settings.
    WindParams wind;
    LodParams lod;
    float density = 1.0f; // vegetation density multiplier; applied (regenerates the tile) by applyDensity
    bool msaa = true;     // 4x MSAA; a change rebuilds the renderer
    float exposure = 0.5f;
    bool lodColors = false, activeFields = false, updatedPlants = false, clusterBounds = false, colliders = false;
    bool paused = false;
    bool keysHelp = false; // the window listing every key and mouse action (F1 or ?)
    // One-shot requests from buttons.
    bool applyDensity = false, step = false, screenshot = false, reload = false, toggleDrive = false;
    // Read-only information.
    std::string scene, device;
    bool driving = false;
    uint64_t tick = 0;
    size_t activeFieldCount = 0, fieldCount = 0, contacts = 0;
    double cameraSpeed = 0.0, simulationSeconds = 0.0, collisionMs = 0.0;
    // A world of several tiles (worldTiles 0: a one-tile scene).
    uint32_t worldTiles = 0, worldPending = 0;
    uint64_t worldGenerated = 0, worldEvicted = 0;
    double worldMiB = 0.0, worldBudgetMiB = 0.0;
    std::vector<std::pair<std::string, double>> passTimes; // GPU milliseconds per pass, latest completed frame
    std::vector<float> frameTimes;                         // milliseconds, oldest first
    std::string message;                                   // last event (screenshot written, reload error, ...)
};

class Ui {
public:
    Ui(Context& ctx, GLFWwindow* window, const Swapchain& swapchain);
    ~Ui();
    Ui(const Ui&) = delete;
    Ui& operator=(const Ui&) = delete;

    // Starts an ImGui frame and builds the panel from `state` (edits are written back).
    void panel(PanelState& state);
    // Renders the panel onto swapchain image `imageIndex` (in COLOR_ATTACHMENT_OPTIMAL, left so).
    void record(VkCommandBuffer cmd, const Swapchain& swapchain, uint32_t imageIndex);
    // True while the mouse / keyboard is over or typing into the panel: the camera must not react then.
    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    void createFramebuffers(const Swapchain& swapchain);
    void destroyFramebuffers();

    Context& ctx_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    std::vector<VkFramebuffer> framebuffers_;
    uint64_t generation_ = 0;
    VkExtent2D extent_{};
};

} // namespace sward
