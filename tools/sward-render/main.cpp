// sward-render: offline renderer. Parses the command line and runs the render job; nothing else.
#include "dataset/dataset_writer.h"
#include "engine/device.h"
#include "render/render_job.h"
#include "scene/scene.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"sward-render: render a sward scene to a stereo dataset: HDR EXR colour, depth, disparity, semantic "
                 "and instance ground truth"};
    sward::RenderJobOptions options;
    app.add_option("scene", options.scenePath, "Scene JSON file (default: the scene format's built-in defaults)");
    app.add_option("--out,-o", options.outDir, "Output folder (created if missing)")->capture_default_str();
    sward::addChecked(app, "--resolution", options.resolution,
                      "Image size WIDTHxHEIGHT, e.g. 1280x720 (each side 1..16384, at most 8192x8192 pixels)", "WxH",
                      [](const std::string& text) {
                          uint32_t width = 0, height = 0;
                          sward::parseResolution(text, width, height);
                      });
    sward::addSamples(app, options.samples, "MSAA samples: 1 or 4");
    app.add_option("--device", options.device, sward::kDeviceOptionHelp);
    bool listOnly = false;
    app.add_flag("--list-devices", listOnly, "List the Vulkan devices (index, UUID, type, name, driver) and exit");
    sward::addPoint(app, "--camera", options.cameraPosition, "Camera position X,Y,Z in world metres");
    sward::addPoint(app, "--look-at", options.cameraLookAt, "Camera target X,Y,Z in world metres");
    sward::addReal(app, "--fov", options.fovYDegrees, 1.0, 170.0, "Vertical field of view in degrees");
    sward::addChecked(app, "--frames", options.frames,
                      "Frame range A:B (frames A .. B-1, B <= 1000000); default: the scene's sequence", "A:B",
                      [](const std::string& text) {
                          uint32_t first = 0, end = 0;
                          sward::parseFrameRange(text, first, end);
                      });
    sward::addChecked(app, "--shard", options.shard,
                      "Render only block I of N of the frames, I/N (e.g. 0/4, N <= 1000000): for job arrays", "I/N",
                      [](const std::string& text) {
                          uint32_t index = 0, count = 0;
                          sward::parseShard(text, index, count);
                      });
    sward::addUnsigned(app, "--seed", options.seed, 0, UINT64_MAX,
                       "Override the scene's seed (terrain, plants, gusts, sensor noise)");
    app.add_option("--allow-assets", options.allowAssets,
                   "Also read the scene's assets from this folder (repeatable; default: the scene's folder only)");
    app.add_flag("--quiet,-q", options.quiet, "No progress line");
    sward::addReal(app, "--time", options.time, 0.0, 1e9, "Time offset in seconds added to every frame's wind");
    app.add_flag("--no-vegetation", options.noVegetation, "Render the same scene without vegetation");
    app.add_flag("--overwrite", options.overwrite,
                 "Remove the dataset already in --out (sward's files only) and start over, e.g. after changing an option");
    app.add_flag("--validation", options.validation, "Enable Vulkan validation; any message fails the run");
    return sward::runTool(app, argc, argv, "sward-render", [&] {
        if (listOnly) {
            std::printf("%s", sward::describeDevices(sward::listDevices()).c_str());
            return 0;
        }
        std::printf("sward-render: %s\n", sward::runRenderJob(options).summary.c_str());
        return 0;
    });
}
