// sward-render: offline renderer. Parses the command line and runs the render job; nothing else.
#include "common/error.h"
#include "render/render_job.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

namespace {

glm::dvec3 parseVec3(const std::string& text, const char* option) {
    glm::dvec3 v;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &extra) != 3 || !std::isfinite(v.x) ||
        !std::isfinite(v.y) || !std::isfinite(v.z))
        throw sward::Error(std::string("bad ") + option + " '" + text + "': expected X,Y,Z in metres");
    return v;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"sward-render: render a sward scene to a stereo dataset: HDR EXR colour, depth, disparity, semantic and instance ground truth"};
    sward::RenderJobOptions options;
    std::string resolution, position, lookAt;
    std::optional<uint32_t> samples;
    std::optional<double> fov;
    app.add_option("scene", options.scenePath, "Scene JSON file (default: the scene format's built-in defaults)");
    app.add_option("--out,-o", options.outDir, "Output folder (created if missing)")->capture_default_str();
    app.add_option("--resolution", resolution, "Image size WIDTHxHEIGHT, e.g. 1280x720");
    app.add_option("--samples", samples, "MSAA samples: 1 or 4");
    app.add_option("--device", options.device, "Vulkan device name substring (also SWARD_DEVICE)");
    app.add_option("--camera", position, "Camera position X,Y,Z in world metres");
    app.add_option("--look-at", lookAt, "Camera target X,Y,Z in world metres");
    app.add_option("--fov", fov, "Vertical field of view in degrees");
    std::string frames;
    app.add_option("--frames", frames, "Frame range A:B (frames A .. B-1); default: the scene's sequence");
    std::string shard;
    app.add_option("--shard", shard, "Render only block I of N of the frames, I/N (e.g. 0/4): for job arrays");
    std::optional<uint64_t> seed;
    app.add_option("--seed", seed, "Override the scene's seed (terrain, plants, gusts, sensor noise)");
    app.add_flag("--quiet,-q", options.quiet, "No progress line");
    app.add_option("--time", options.time, "Time offset in seconds added to every frame's wind")->capture_default_str();
    app.add_flag("--no-vegetation", options.noVegetation, "Render the same scene without vegetation");
    app.add_flag("--overwrite", options.overwrite,
                 "Remove the dataset already in --out (sward's files only) and start over, e.g. after changing an option");
    app.add_flag("--validation", options.validation, "Enable Vulkan validation; any message fails the run");
    return sward::runTool(app, argc, argv, "sward-render", [&] {
        if (!resolution.empty()) options.resolution = resolution;
        if (!frames.empty()) options.frames = frames;
        if (!shard.empty()) options.shard = shard;
        options.seed = seed;
        options.samples = samples;
        options.fovYDegrees = fov;
        if (!position.empty()) options.cameraPosition = parseVec3(position, "--camera");
        if (!lookAt.empty()) options.cameraLookAt = parseVec3(lookAt, "--look-at");
        sward::runRenderJob(options);
        return 0;
    });
}
