// sward-view: look at a scene live (issue 9). A GLFW window and a Vulkan swapchain around the same engine,
// SceneRenderer and Simulation as sward-render: fly or drive the rover through the grass, watch the fields the
// interaction activates, change wind / LOD / density / MSAA, time the passes, save screenshots.
//
// Frame: [interaction tick] -> SceneRenderer::record (expansion, shadow, main + overlay lines, resolve)
//        -> present pass (tonemap the resolved HDR image into the swapchain image) -> panel -> present.
// Two frames are in flight; the Swapchain's per-frame serials are their fences.
//
// Files: viewer.cpp wires the pieces and runs the frame loop; window (GLFW + surface), scene_state (what a scene
// file builds), input (keys, mouse), rover_control (the keyboard rover), fly_camera, overlay (debug lines),
// present_pass (tonemap into the swapchain), ui (the panel), screenshots (image files), test_hooks (scripted
// window changes and key presses).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sward {

struct ViewerOptions {
    std::string scenePath;               // empty: examples/meadow.json
    std::vector<std::string> allowAssets; // --allow-assets: more folders the scene may read assets from
    std::string device;                  // Vulkan device name substring
    bool validation = false;             // also SWARD_VALIDATION
    uint32_t width = 1280, height = 720; // initial window size
    std::optional<uint32_t> samples;     // 1 or 4; default: the scene's
    bool vsync = true;
    bool showUi = true;
    std::string overlays;                // comma list: lod,active-fields,updated-plants,clusters,colliders
    bool drive = false;                  // start driving the rover (camera follows)
    double autodrive = 0.0;              // m/s: the rover drives itself straight ahead (captures, tests)
    std::optional<glm::dvec3> camera, lookAt; // initial fly camera (world metres) instead of the scene's
    std::string screenshotDir = "screenshots";

    // Headless checks: render `frames` frames through the swapchain, then write the last presented image to
    // `screenshot` (PNG) and exit. 0 = interactive.
    uint32_t frames = 0;
    std::string screenshot;
    std::optional<std::pair<uint32_t, std::string>> resizeAt; // at frame N, resize the window to "WxH"
    std::optional<uint32_t> minimizeAt;                       // at frame N minimise, at N + 2 restore
    // Key presses injected at frames, "FRAME:KEY,..." (KEY: a-z, 0-9, space, f12, esc), handled exactly as
    // typed keys: e.g. "5:m,12:f12" toggles MSAA at frame 5 and takes a screenshot at frame 12.
    std::string press;
};

// Runs the viewer until the window closes (or `frames` frames). Throws sward::Error on failure, including when
// Vulkan validation reported any message.
void runViewer(const ViewerOptions& options);

} // namespace sward
