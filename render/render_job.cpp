#include "render/render_job.h"

#include "vegetation/atlas.h"
#include "engine/context.h"
#include "dataset/dataset_writer.h"
#include "dataset/frame_record.h"
#include "scene/scene.h"
#include "render/scene_renderer.h"
#include "io/sha256.h"
#include "render/simulation.h"
#include "render/vegetation_renderer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <unistd.h>

#ifndef SWARD_REVISION
#define SWARD_REVISION "unknown"
#endif

namespace sward {

namespace {

struct Progress {
    using Clock = std::chrono::steady_clock;
    bool enabled;
    uint32_t total;
    Clock::time_point start = Clock::now();
    void frameDone(uint32_t done, uint32_t frame) const {
        if (!enabled) return;
        double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        double fps = done / std::max(elapsed, 1e-9);
        std::fprintf(stderr, "\rsward-render: frame %u (%u/%u)  %.2f frames/s  ETA %.0f s   ", frame, done, total, fps,
                     double(total - done) / fps);
        if (done == total) std::fprintf(stderr, "\n");
    }
};

} // namespace

void runRenderJob(const RenderJobOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();

    // Everything that can be checked without a GPU is checked first, so bad input fails fast and writes nothing.
    Scene scene;
    if (options.scenePath.empty()) {
        nlohmann::json json = nlohmann::json::object();
        if (options.seed) json["seed"] = *options.seed;
        scene = parseScene(json, "<built-in>");
    } else {
        std::ifstream file(options.scenePath);
        if (!file) throw Error("cannot open scene file '" + options.scenePath + "'");
        nlohmann::json json;
        try {
            json = nlohmann::json::parse(file);
        } catch (const nlohmann::json::parse_error& e) {
            throw Error("scene file '" + options.scenePath + "' is not valid JSON: " + e.what());
        }
        if (options.seed && json.is_object()) json["seed"] = *options.seed; // before parsing: every seed follows it
        scene = parseScene(json, options.scenePath);
    }
    uint32_t width = scene.render.width, height = scene.render.height;
    if (options.resolution) parseResolution(*options.resolution, width, height);
    uint32_t samples = options.samples.value_or(scene.render.samples);
    require(std::isfinite(options.time) && options.time >= 0.0, "--time must be a finite, non-negative number of seconds");
    require(samples == 1 || samples == 4, "--samples must be 1 or 4 (got " + std::to_string(samples) + ")");
    if (options.cameraPosition) {
        scene.camera.position = *options.cameraPosition;
        scene.camera.useHeightAboveGround = false;
        scene.camera.hasPath = false;
        scene.camera.rig.mountObject.clear();
    }
    if (options.cameraLookAt) { // a fixed target needs a fixed camera: the scene's position unless --camera
        scene.camera.lookAt = *options.cameraLookAt;
        scene.camera.lookAtUsesGround = false;
        scene.camera.hasPath = false;
        scene.camera.rig.mountObject.clear();
    }
    if (options.fovYDegrees) {
        require(*options.fovYDegrees >= 1.0 && *options.fovYDegrees <= 170.0, "--fov must be between 1 and 170 degrees");
        scene.camera.fovYDegrees = *options.fovYDegrees;
    }
    uint32_t firstFrame = 0, endFrame = scene.sequence.frames;
    if (options.frames) {
        parseFrameRange(*options.frames, firstFrame, endFrame);
        require(endFrame <= scene.sequence.frames,
                "--frames " + *options.frames + " goes past the scene's sequence of " +
                    std::to_string(scene.sequence.frames) + " frame(s) (sequence.frames)");
    }
    uint32_t shardIndex = 0, shardCount = 1;
    if (options.shard) {
        parseShard(*options.shard, shardIndex, shardCount);
        shardRange(firstFrame, endFrame, shardIndex, shardCount, firstFrame, endFrame);
    }

    Heightfield terrain = buildTerrain(scene);
    std::vector<ObjectModel> models = loadObjectModels(scene.objects, scene.source);
    // All CPU-side loading (and its errors) happens before the GPU is touched or a file is written.
    const bool withVegetation = scene.vegetationEnabled && !options.noVegetation;
    std::optional<VegetationTile> vegetation;
    std::optional<Atlas> atlas;
    if (withVegetation) {
        vegetation = buildVegetation(scene, terrain);
        atlas = buildAtlas(scene);
        require(atlas->desc.rows.size() >= scene.vegetation.categoryCount,
                scene.source + ": the atlas has " + std::to_string(atlas->desc.rows.size()) + " rows but 'vegetation' has " +
                    std::to_string(scene.vegetation.categoryCount) + " categories (one row per category)");
    }
    const RigParams& rig = scene.camera.rig;
    auto rigAt = [&](uint32_t frame) {
        return sceneRig(scene, terrain, models, width, height, double(frame) * scene.sequence.timeStep);
    };
    RigCameras firstRig;
    try { // also checks the mount before anything is written
        firstRig = rigAt(firstFrame);
    } catch (const Error& e) {
        throw Error(scene.source + ": 'camera.mount': " + e.what());
    }

    // The sensor model checks its lens (invertible over the image) when built: before anything is written.
    std::optional<SensorModel> sensor;
    if (rig.sensor.enabled) {
        try {
            sensor.emplace(rig.sensor, Intrinsics::of(firstRig.left));
        } catch (const Error& e) {
            throw Error(scene.source + ": 'camera.sensor': " + e.what());
        }
    }

    DatasetWriter dataset(options.outDir, rig.stereo());
    dataset.prepare();
    if (rig.stereo()) dataset.writeCalib(firstRig.left, rig.baseline, rig.minDepth);

    // frames.jsonl covers the scene's whole sequence, whatever this run renders: every record is a pure function
    // of the scene and the tick, so shards and resumed runs write the very same file.
    std::vector<nlohmann::json> records;
    for (uint32_t frame = 0; frame < scene.sequence.frames; ++frame)
        records.push_back(frameRecord(scene, models, terrain, rigAt(frame), frame, options.time, withVegetation));
    dataset.writeFrameLog(records);

    std::vector<uint32_t> todo;
    for (uint32_t frame = firstFrame; frame < endFrame; ++frame)
        if (!dataset.frameComplete(frame)) todo.push_back(frame);
    const uint32_t skipped = (endFrame - firstFrame) - uint32_t(todo.size());

    Context ctx(DeviceOptions{.deviceFilter = options.device, .validation = options.validation || DeviceOptions{}.validation});
    {
        SceneRenderer renderer(ctx, scene, terrain, samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                               vegetation ? &*vegetation : nullptr, atlas ? &*atlas : nullptr, &models);
        // The interaction simulation reads the tile's static records on the CPU; without colliders the upload
        // is all that is needed and the CPU copy goes.
        std::optional<Simulation> simulation;
        if (renderer.vegetation() && sceneHasColliders(scene)) {
            simulation.emplace(ctx, scene, terrain, *vegetation, renderer.vegetation()->buffers());
            simulation->setObjectModels(&models);
        } else {
            vegetation.reset();
        }

        OffscreenFrame target(ctx, width, height, samples);
        Progress progress{!options.quiet && isatty(fileno(stderr)), uint32_t(todo.size())};
        uint32_t done = 0;
        for (uint32_t frame : todo) {
            const double time = double(frame) * scene.sequence.timeStep;
            RigCameras cameras = rigAt(frame);
            std::function<void(VkCommandBuffer)> tick;
            if (simulation) {
                simulation->runTicksBefore(frame); // ticks of frames skipped or rendered elsewhere (shards)
                tick = [&](VkCommandBuffer cmd) { simulation->recordNextTick(cmd, frame); };
            }
            FrameImages images = target.render(renderer, cameras.left, options.time + time, frame, tick,
                                               rig.stereo() ? &cameras.right : nullptr);
            if (sensor) {
                sensor->applyHalf(scene.seed, frame, 0, images.rgbaHalf);
                if (rig.stereo()) sensor->applyHalf(scene.seed, frame, 1, images.rightRgbaHalf);
            }
            dataset.writeFrame(frame, images, cameras.left, rig.baseline);
            progress.frameDone(++done, frame);
        }
    }
    uint32_t messages = ctx.device.validationMessageCount();
    require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");

    // The manifest: everything needed to reproduce and verify the files, and nothing that changes between two
    // runs of the same command (no dates, no timings), so identical datasets have identical manifests.
    std::vector<std::string> files = {"frames.jsonl"};
    if (rig.stereo()) files.push_back("calib.txt");
    for (uint32_t frame = firstFrame; frame < endFrame; ++frame)
        for (std::string& file : dataset.frameFiles(frame)) files.push_back(std::move(file));
    nlohmann::json options_ = {{"resolution", std::to_string(width) + "x" + std::to_string(height)},
                               {"samples", samples},
                               {"no_vegetation", options.noVegetation},
                               {"time", options.time}};
    if (options.cameraPosition || options.cameraLookAt || options.fovYDegrees) options_["camera_override"] = true;
    std::string sceneHash = options.scenePath.empty() ? sha256Hex(std::string_view("<built-in>"))
                                                      : sha256File(options.scenePath);
    nlohmann::json info = {{"format", "sward-dataset-1"},
                           {"scene", options.scenePath.empty() ? "<built-in>" : options.scenePath},
                           {"scene_sha256", sceneHash},
                           {"seed", scene.seed},
                           {"frames", {firstFrame, endFrame}},
                           {"shard", options.shard ? nlohmann::json(*options.shard) : nlohmann::json(nullptr)},
                           {"options", options_},
                           {"sward_revision", SWARD_REVISION},
                           {"device", ctx.device.name()},
                           {"driver", ctx.device.driver()}};
    std::string manifest = options.shard ? "manifest.shard-" + std::to_string(shardIndex) + "-of-" +
                                               std::to_string(shardCount) + ".json"
                                         : "manifest.json";
    dataset.writeManifest(manifest, info, files);

    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("sward-render: %s, frames %u:%u (%zu rendered, %u already complete), %ux%u, %ux MSAA, %s -> %s in %.2f s\n",
                scene.name.c_str(), firstFrame, endFrame, todo.size(), skipped, width, height, samples,
                rig.stereo() ? "stereo" : "mono", options.outDir.c_str(), seconds);
}

void parseFrameRange(const std::string& text, uint32_t& first, uint32_t& end) {
    unsigned a = 0, b = 0;
    char colon = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &colon, &b, &extra) != 3 || colon != ':' || a >= b ||
        text.find_first_not_of("0123456789:") != std::string::npos)
        throw Error("bad frame range '" + text + "': expected A:B with A < B (frames A .. B-1), e.g. 0:60");
    first = a;
    end = b;
}

} // namespace sward
