// sward-view: interactive viewer of a sward scene (see viewer.h and README "Viewer"). Parses the command line and
// runs the viewer; nothing else.
#include "common/error.h"
#include "common/parse_number.h"
#include "engine/device_choice.h"
#include "scene/scene.h"
#include "test_hooks.h"
#include "viewer.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

namespace {

// Frames a headless run may ask for: far beyond any test or capture, short of a run that never ends.
constexpr uint64_t kMaxViewerFrames = 100000000;

// The test hooks' options, checked while parsing so a bad value is a usage error, not a failure mid-run.
void addTestHooks(CLI::App& app, sward::ViewerOptions& options) {
    app.add_option_function<std::vector<std::string>>(
           "--resize-at",
           [&options](const std::vector<std::string>& values) {
               uint32_t width = 0, height = 0;
               sward::parseResolution(values.at(1), width, height);
               options.resizeAt.emplace(
                   uint32_t(sward::parseUnsigned(values.at(0), 0, kMaxViewerFrames, "--resize-at frame")),
                   values.at(1));
           },
           "Test hook: at frame N resize the window to WxH (N WxH)")
        ->expected(2)
        ->type_name("N WxH");
    sward::addUnsigned(app, "--minimize-at", options.minimizeAt, 0, kMaxViewerFrames,
                       "Test hook: minimise the window at frame N, restore at N+2");
    sward::addChecked(app, "--press", options.press,
                      "Test hook: key presses at frames, FRAME:KEY,... (e.g. 5:m,12:f12)", "FRAME:KEY,...",
                      [](const std::string& text) { sward::parsePresses(text); });
}

} // namespace

int main(int argc, char** argv) {
    sward::ViewerOptions options;
    CLI::App app{"sward-view: fly or drive through a sward scene and watch the interaction live"};
    app.add_option("scene", options.scenePath, "Scene JSON file (default: examples/meadow.json)");
    app.add_option("--allow-assets", options.allowAssets,
                   "Also read the scene's assets from this folder (repeatable; default: the scene's folder only)");
    std::string size;
    sward::addChecked(app, "--size", size, "Initial window size WIDTHxHEIGHT (default 1280x720)", "WxH",
                      [](const std::string& text) {
                          uint32_t width = 0, height = 0;
                          sward::parseResolution(text, width, height);
                      });
    sward::addSamples(app, options.samples, "MSAA samples: 1 or 4 (default: the scene's)");
    app.add_option("--device", options.device, sward::kDeviceOptionHelp);
    app.add_flag("--validation", options.validation, "Enable Vulkan validation; any message fails the run");
    app.add_flag("!--no-vsync", options.vsync, "Present as fast as possible (mailbox / immediate)");
    app.add_flag("!--no-ui", options.showUi, "Start with the panel hidden (H toggles it)");
    app.add_option("--overlay", options.overlays,
                   "Overlays on at start, comma-separated: lod, active-fields, updated-plants, clusters, colliders");
    app.add_flag("--drive", options.drive, "Start driving the rover (F toggles)");
    sward::addReal(app, "--autodrive", options.autodrive, -100.0, 100.0,
                   "The rover drives itself straight ahead at this speed, m/s");
    app.add_option("--screenshot-dir", options.screenshotDir, "Folder for F12 screenshots")->capture_default_str();
    CLI::Option* frames = sward::addUnsigned(app, "--frames", options.frames, 1, kMaxViewerFrames,
                                             "Render this many frames through the swapchain, then exit");
    app.add_option("--screenshot", options.screenshot, "With --frames: write the last presented frame to this PNG")
        ->needs(frames);
    addTestHooks(app, options);
    CLI::Option* camera =
        sward::addPoint(app, "--camera", options.camera, "Initial camera position X,Y,Z in world metres");
    sward::addPoint(app, "--look-at", options.lookAt, "Initial camera target X,Y,Z in world metres")->needs(camera);
    return sward::runTool(app, argc, argv, "sward-view", [&] {
        if (!size.empty()) sward::parseResolution(size, options.width, options.height);
        sward::runViewer(options);
        return 0;
    });
}
