// sward-bench: prints benchmark figures (and writes them as JSON with --json). Thin: parsing and printing only.
#include "common/atomic_file.h"
#include "engine/device_choice.h"
#include "range/range_benchmark.h"
#include "render/bench_suite.h"
#include "render/benchmarks.h"
#include "scene/scene.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace {

// Prints every key except `tableKey` (printed as a table by the caller) and writes the JSON file atomically.
void emit(const nlohmann::json& result, const std::string& jsonPath, const std::string& tableKey = "") {
    for (auto it = result.begin(); it != result.end(); ++it)
        if (it.key() != tableKey) std::printf("%-32s %s\n", it.key().c_str(), it.value().dump().c_str());
    if (jsonPath.empty()) return;
    sward::writeTextAtomically(jsonPath, result.dump(2) + "\n");
}

CLI::App* addLidarCommand(CLI::App& app, sward::LidarBenchOptions& lidar, std::string& json) {
    CLI::App* ldr = app.add_subcommand(
        "lidar", "Range sensor against real time: a sensor driving through the scene (CPU, Embree), sweep time, CPU "
                 "time and points per second");
    ldr->add_option("scene", lidar.scenePath, "Scene JSON (default: examples/meadow.json)");
    ldr->add_option("--allow-assets", lidar.allowAssets, "Also read the scene's assets from this folder (repeatable)");
    ldr->add_option("--preset", lidar.preset,
                    "Sensor preset (VLP-16, HDL-32E, OS1-64, LMS111, UST-10LX, AzureKinect-NFOV)")
        ->capture_default_str();
    sward::addReal(*ldr, "--height", lidar.height, 0.0, 100.0, "Sensor height above the ground, metres");
    sward::addReal(*ldr, "--speed", lidar.speed, 0.0, 100.0, "Driving speed, metres per second");
    sward::addUnsigned(*ldr, "--sub-rays", lidar.subRays, 0, 19,
                       "Rays per beam: 1 (no divergence), 7 or 19 (0: the preset's)");
    sward::addUnsigned(*ldr, "--sweeps", lidar.sweeps, 1, 10000, "Measured sweeps (medians)");
    sward::addUnsigned(*ldr, "--threads", lidar.threads, 0, sward::kMaxThreadsOption, "Threads (0 = all cores)");
    ldr->add_option("--json", json, "Also write the figures as a JSON object to this file");
    return ldr;
}

CLI::App* addDatasetCommand(CLI::App& app, sward::DatasetBenchOptions& options, std::string& json) {
    CLI::App* dst = app.add_subcommand(
        "dataset", "sward-render's whole job (render, read back, write every file) into a temporary folder: frames per "
                   "second after the first frame, CPU time per frame, and render, write and wait time per frame");
    dst->add_option("scene", options.scenePath, "Scene JSON (default: examples/rover-track.json)");
    dst->add_option("--allow-assets", options.allowAssets,
                    "Also read the scene's assets from this folder (repeatable)");
    sward::addChecked(*dst, "--resolution", options.resolution, "Image size WIDTHxHEIGHT (default: the scene's)", "WxH",
                      [](const std::string& text) {
                          uint32_t width = 0, height = 0;
                          sward::parseResolution(text, width, height);
                      });
    sward::addSamples(*dst, options.samples, "MSAA samples: 1 or 4 (default: the scene's)");
    sward::addUnsigned(*dst, "--frames", options.frames, 2, 10000,
                       "Frames 0 .. N-1; the figures are over all but the first");
    dst->add_option("--device", options.device, sward::kDeviceOptionHelp);
    dst->add_option("--json", json, "Also write the figures as a JSON object to this file");
    return dst;
}

CLI::App* addWorldCommand(CLI::App& app, sward::WorldBenchOptions& options, std::string& json) {
    CLI::App* wld = app.add_subcommand(
        "world", "World of many tiles, CPU side: tile generation time, resident memory against resident tiles in a "
                 "4 x 4 and a 16 x 16 world");
    wld->add_option("scene", options.scenePath, "Scene JSON with a 'world' (default: examples/world.json)");
    wld->add_option("--allow-assets", options.allowAssets,
                    "Also read the scene's assets from this folder (repeatable)");
    sward::addReal(*wld, "--density-multiplier", options.densityMultiplier, 0.0001, 100.0,
                   "Replaces vegetation.density_multiplier (default: the scene's)");
    sward::addUnsigned(*wld, "--threads", options.threads, 0, sward::kMaxThreadsOption,
                       "Threads per tile generation (0 = all cores)");
    sward::addUnsigned(*wld, "--tiles", options.tiles, 1, 256, "Tiles generated one by one for the generation figures");
    wld->add_flag("--no-gpu", options.noGpu, "CPU figures only (no upload and frame times)");
    wld->add_option("--device", options.device, sward::kDeviceOptionHelp);
    sward::addUnsigned(*wld, "--frames", options.frames, 1, 1000, "Timed frames per resident-tile count");
    wld->add_option("--json", json, "Also write the figures as a JSON object to this file");
    return wld;
}

struct SuiteCommand {
    sward::SuiteOptions options;
    std::string writeReference; // --write-reference DIR: only the cross-check's reference, into DIR
};

CLI::App* addSuiteCommand(CLI::App& app, SuiteCommand& suite) {
    CLI::App* cmd = app.add_subcommand(
        "suite", "Every headline figure in one bounded run, with a correctness cross-check against lavapipe's "
                 "reference: writes suite.json and suite.md into --out (docs/suite.md)");
    cmd->add_option("--out", suite.options.outDir, "Folder for suite.json and suite.md (refused when not empty)");
    cmd->add_flag("--overwrite", suite.options.overwrite, "Replace suite.json / suite.md (or the reference) there");
    cmd->add_flag("--quick", suite.options.quick, "Smaller sizes and fewer frames (< 3 minutes on lavapipe)");
    cmd->add_option("--device", suite.options.device, sward::kDeviceOptionHelp);
    cmd->add_option("--data", suite.options.dataRoot,
                    "Folder holding examples/ and bench/reference/ (default: the installed share/sward, else the "
                    "source tree)");
    cmd->add_option("--only", suite.options.only,
                    "Run only these figures (comma-separated or repeated; the others are "
                    "recorded as skipped)")
        ->delimiter(',')
        ->check(CLI::IsMember(sward::suiteFigureNames()));
    cmd->add_option("--write-reference", suite.writeReference,
                    "Render the cross-check frame and write it as the reference into this folder, nothing else");
    return cmd;
}

int runSuite(const SuiteCommand& suite) {
    if (!suite.writeReference.empty()) {
        const std::string root = suite.options.dataRoot.empty() ? sward::suiteDataRoot() : suite.options.dataRoot;
        std::printf("%s\n", sward::writeSuiteReference(suite.writeReference, suite.options.overwrite, root,
                                                       suite.options.device)
                                .dump(2)
                                .c_str());
        return 0;
    }
    const nlohmann::json result = sward::runBenchSuite(suite.options);
    std::fputs(sward::suiteTable(result).c_str(), stdout);
    return sward::suitePassed(result) ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"sward-bench: measured figures for sward"};
    app.require_subcommand(1);
    std::string json;
    app.add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::GenerateBenchOptions generate;
    CLI::App* gen = app.add_subcommand("generate", "Generate and upload one full tile of plants");
    sward::addReal(*gen, "--density", generate.density, 0.001, 1000.0, "Grass plants per m^2");
    // 8192 m: 4096 cells of the bench ground's 2 m spacing, the largest heightfield ground (world/heightfield.h).
    sward::addReal(*gen, "--tile-size", generate.tileSize, 1.0, 8192.0, "Tile edge in metres");
    sward::addUnsigned(*gen, "--threads", generate.threads, 0, sward::kMaxThreadsOption,
                       "Worker threads (0 = all cores)");
    sward::addUnsigned(*gen, "--repeats", generate.repeats, 1, 1000, "Generation runs (median reported)");
    gen->add_option("--device", generate.device, sward::kDeviceOptionHelp);
    gen->add_flag("!--no-upload", generate.upload, "Skip the GPU upload");
    gen->add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::FrameBenchOptions frame;
    std::string resolution = "1024x768";
    CLI::App* frm = app.add_subcommand("frame", "Render a scene: GPU pass times, fragment lanes per covered pixel, cut-out quads against whole quads, expansion overhead");
    frm->add_option("scene", frame.scenePath, "Scene JSON (default: examples/meadow.json)");
    frm->add_option("--allow-assets", frame.allowAssets,
                    "Also read the scene's assets from this folder (repeatable; default: the scene's folder only)");
    sward::addParsed(*frm, "--resolution", resolution, "WIDTHxHEIGHT", "WxH",
                     [&frame](const std::string& text, const std::string&) {
                         sward::parseResolution(text, frame.width, frame.height);
                         return text;
                     });
    sward::addSamples(*frm, frame.samples, "MSAA samples (1 or 4)");
    sward::addUnsigned(*frm, "--frames", frame.frames, 1, 10000, "Measured frames per figure (medians)");
    frm->add_option_function<std::vector<std::string>>(
           "--cutout-corners",
           [&frame](const std::vector<std::string>& values) {
               frame.cutoutCorners.clear();
               for (const std::string& text : values) {
                   if (text == "0") continue; // whole quads only
                   frame.cutoutCorners.push_back(uint32_t(sward::parseUnsigned(text, 4, 8, "--cutout-corners")));
               }
           },
           "Cut-out variants (corners per polygon, 4..8; 0: none) measured against whole quads (repeatable; default 4 6 8)")
        ->type_name("UINT");
    frm->add_flag(
        "!--no-floor", frame.floor,
        "Skip the floor variants (the main pass with plants drawn by a constant-colour shader, and without plants)");
    frm->add_option("--device", frame.device, sward::kDeviceOptionHelp);
    frm->add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::CollideBenchOptions collide;
    CLI::App* col = app.add_subcommand(
        "collide", "Interaction worst case: one colliding sphere per 5 x 5 m cluster of N fields (CPU collision, "
                   "upload, GPU recovery), 10,000 colliders above the grass, and no GPU work with 0 active fields");
    col->add_option_function<std::vector<std::string>>(
           "--fields",
           [&collide](const std::vector<std::string>& values) {
               collide.fields.clear();
               // The synthetic tile is 500 x 500 m: 400 fields.
               for (const std::string& text : values)
                   collide.fields.push_back(uint32_t(sward::parseUnsigned(text, 1, 400, "--fields")));
           },
           "Fields with colliders, one case per value (repeatable; default 10 100 400)")
        ->type_name("UINT");
    sward::addUnsigned(*col, "--ticks", collide.ticks, 1, 1000000, "Measured ticks per case (medians)");
    sward::addUnsigned(*col, "--warmup", collide.warmup, 0, 1000000, "Ticks per case before measuring");
    sward::addUnsigned(*col, "--threads", collide.threads, 0, sward::kMaxThreadsOption,
                       "Collision threads (0 = all cores)");
    sward::addReal(*col, "--density", collide.density, 0.001, 1000.0, "Grass plants per m^2");
    sward::addReal(*col, "--radius", collide.radius, 0.001, 2.0, "Collider sphere radius, metres");
    sward::addReal(*col, "--tick-rate", collide.tickRate, 0.0, 1000.0,
                   "Ticks per second, paced like a real-time loop (threads idle between ticks); 0 = back to back");
    col->add_option("--device", collide.device, sward::kDeviceOptionHelp);
    col->add_flag("!--no-gpu", collide.gpu, "CPU collision only: no Vulkan device, no upload or GPU figures");
    col->add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::WorldBenchOptions world;
    CLI::App* wld = addWorldCommand(app, world, json);

    sward::LidarBenchOptions lidar;
    CLI::App* ldr = addLidarCommand(app, lidar, json);

    sward::DatasetBenchOptions dataset;
    CLI::App* dst = addDatasetCommand(app, dataset, json);

    SuiteCommand suite;
    CLI::App* ste = addSuiteCommand(app, suite);

    return sward::runTool(app, argc, argv, "sward-bench", [&] {
        if (ste->parsed()) return runSuite(suite);
        if (ldr->parsed()) emit(sward::benchLidar(lidar), json);
        if (dst->parsed()) emit(sward::benchDataset(dataset), json);
        if (gen->parsed()) emit(sward::benchGenerate(generate), json);
        if (frm->parsed()) emit(sward::benchFrame(frame), json);
        if (wld->parsed()) {
            nlohmann::json result = sward::benchWorld(world);
            std::fputs(sward::worldTable(result).c_str(), stdout);
            emit(result, json, "memory");
        }
        if (col->parsed()) {
            nlohmann::json result = sward::benchCollide(collide);
            std::fputs(sward::collideTable(result).c_str(), stdout);
            emit(result, json, "results");
        }
        return 0;
    });
}
