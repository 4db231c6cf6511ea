// sward-view: interactive viewer of a sward scene (see viewer.h and README "Viewer").
#include "common/error.h"
#include "scene/scene.h"
#include "viewer.h"

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    sward::ViewerOptions options;
    CLI::App app{"sward-view: fly or drive through a sward scene and watch the interaction live"};
    app.add_option("scene", options.scenePath, "Scene JSON file (default: examples/meadow.json)");
    app.add_option("--allow-assets", options.allowAssets,
                   "Also read the scene's assets from this folder (repeatable; default: the scene's folder only)");
    std::string size;
    app.add_option("--size", size, "Initial window size WIDTHxHEIGHT (default 1280x720)");
    app.add_option("--samples", options.samples, "MSAA samples: 1 or 4 (default: the scene's)");
    app.add_option("--device", options.device, "Vulkan device name substring (also SWARD_DEVICE)");
    app.add_flag("--validation", options.validation, "Enable Vulkan validation; any message fails the run");
    app.add_flag("!--no-vsync", options.vsync, "Present as fast as possible (mailbox / immediate)");
    app.add_flag("!--no-ui", options.showUi, "Start with the panel hidden (H toggles it)");
    app.add_option("--overlay", options.overlays,
                   "Overlays on at start, comma-separated: lod, active-fields, updated-plants, clusters, colliders");
    app.add_flag("--drive", options.drive, "Start driving the rover (F toggles)");
    app.add_option("--autodrive", options.autodrive, "The rover drives itself straight ahead at this speed, m/s");
    app.add_option("--screenshot-dir", options.screenshotDir, "Folder for F12 screenshots")->capture_default_str();
    app.add_option("--frames", options.frames, "Render this many frames through the swapchain, then exit");
    app.add_option("--screenshot", options.screenshot, "With --frames: write the last presented frame to this PNG");
    app.add_option("--resize-at", options.resizeAt, "Test hook: at frame N resize the window to WxH (N WxH)");
    app.add_option("--minimize-at", options.minimizeAt, "Test hook: minimise the window at frame N, restore at N+2");
    app.add_option("--press", options.press, "Test hook: key presses at frames, FRAME:KEY,... (e.g. 5:m,12:f12)");
    std::string camera, lookAt;
    app.add_option("--camera", camera, "Initial camera position X,Y,Z in world metres");
    app.add_option("--look-at", lookAt, "Initial camera target X,Y,Z in world metres");
    CLI11_PARSE(app, argc, argv);
    try {
        if (!size.empty()) sward::parseResolution(size, options.width, options.height);
        auto point = [](const std::string& text, const char* option) {
            double x, y, z;
            char extra;
            if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &extra) != 3)
                throw sward::Error(std::string(option) + " must be X,Y,Z in metres (got '" + text + "')");
            return glm::dvec3(x, y, z);
        };
        if (!camera.empty()) options.camera = point(camera, "--camera");
        if (!lookAt.empty()) options.lookAt = point(lookAt, "--look-at");
        sward::require(!options.lookAt || options.camera, "--look-at needs --camera");
        sward::require(options.screenshot.empty() || options.frames > 0, "--screenshot needs --frames N");
        sward::runViewer(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sward-view: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
