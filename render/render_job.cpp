#include "render/render_job.h"

#include "common/background_task.h"
#include "common/input_file.h"
#include "common/json_reader.h"
#include "common/parse_number.h"
#include "common/stopwatch.h"
#include "dataset/dataset_writer.h"
#include "dataset/fingerprint.h"
#include "dataset/frame_record.h"
#include "dataset/naming.h"
#include "engine/context.h"
#include "io/sha256.h"
#include "range/range_recorder.h"
#include "render/auto_exposure.h"
#include "render/motion_blur.h"
#include "render/rolling_shutter.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/scene_input.h"
#include "scene/scene_resources.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <unistd.h>
#include <utility>

#ifndef SWARD_REVISION
#define SWARD_REVISION "unknown"
#endif

namespace sward {

namespace {

struct Progress {
    bool enabled;
    uint32_t total;
    Stopwatch elapsed;
    void frameDone(uint32_t done, uint32_t frame) const {
        if (!enabled) return;
        const double seconds = elapsed.seconds();
        double fps = done / std::max(seconds, 1e-9);
        std::fprintf(stderr, "\rsward-render: frame %u (%u/%u)  %.2f frames/s  ETA %.0f s   ", frame, done, total, fps,
                     double(total - done) / fps);
        if (done == total) std::fprintf(stderr, "\n");
    }
};

// The run's clock and the report it fills (RenderJobReport): frame f's entry is sized before the writer's thread
// fills its part, and read only after the writer has finished.
struct JobClock {
    Stopwatch run = Stopwatch::withCpuTime();
    RenderJobReport report;

    double now() const { return run.seconds(); }
    // Runs `write` (a frame's files) and records how long it took, when it ended and the process's CPU time then.
    void timeWrite(RenderJobReport::Frame& frame, const std::function<void()>& write) const {
        const double begin = now();
        write();
        frame.doneSeconds = now();
        frame.writeSeconds = frame.doneSeconds - begin;
        frame.cpuSeconds = run.cpuMs() / 1000.0;
    }
};

// What this run renders, from the scene and the command line, checked before anything is built.
struct JobPlan {
    uint32_t width = 0, height = 0, samples = 0;
    uint32_t firstFrame = 0, endFrame = 0; // [first, end) of this run (after --frames and --shard)
    uint32_t shardIndex = 0, shardCount = 1;
};

SceneInput sceneInput(const RenderJobOptions& options) {
    return SceneInput{.path = options.scenePath, .text = options.sceneText, .overrides = options.overrides,
                      .seed = options.seed, .allowedAssetDirs = options.allowAssets};
}

// The scene is the file as it is: no text instead of it and no override ("{}" is none; the overrides were parsed
// by loadSceneInput before this is asked).
bool sceneIsTheFile(const RenderJobOptions& options) {
    return !options.sceneText && (options.overrides.empty() || nlohmann::json::parse(options.overrides).empty());
}

// The scene's SHA-256 in the fingerprint: of the file as it is (so datasets made before overrides existed keep
// their fingerprint), else of the document actually parsed (text, overrides).
std::string sceneHash(const RenderJobOptions& options) {
    if (!sceneIsTheFile(options)) {
        SceneInput input = sceneInput(options);
        input.seed.reset(); // the seed is a fingerprint key of its own
        return sha256Hex(std::string_view(sceneInputJson(input).dump()));
    }
    return options.scenePath.empty() ? sha256Hex(std::string_view("<built-in>")) : sha256File(options.scenePath);
}

JobPlan planJob(Scene& scene, const RenderJobOptions& options) {
    JobPlan plan{.width = scene.render.width, .height = scene.render.height};
    if (options.resolution) parseResolution(*options.resolution, plan.width, plan.height);
    plan.samples = options.samples.value_or(scene.render.samples);
    require(std::isfinite(options.time) && options.time >= 0.0, "--time must be a finite, non-negative number of seconds");
    require(plan.samples == 1 || plan.samples == 4, "--samples must be 1 or 4 (got " + std::to_string(plan.samples) + ")");
    overrideCamera(scene, options.cameraPosition, options.cameraLookAt, options.fovYDegrees);
    plan.endFrame = scene.sequence.frames;
    if (options.frames) {
        parseFrameRange(*options.frames, plan.firstFrame, plan.endFrame);
        require(plan.endFrame <= scene.sequence.frames,
                "--frames " + *options.frames + " goes past the scene's sequence of " +
                    std::to_string(scene.sequence.frames) + " frame(s) (sequence.frames)");
    }
    if (options.shard) {
        parseShard(*options.shard, plan.shardIndex, plan.shardCount);
        shardRange(plan.firstFrame, plan.endFrame, plan.shardIndex, plan.shardCount, plan.firstFrame, plan.endFrame);
    }
    return plan;
}

// The frames.jsonl records. They cover the scene's whole sequence, whatever this run renders: every record is a
// pure function of the scene and the tick, so shards and resumed runs write the very same file.
std::vector<nlohmann::json> sequenceRecords(const SceneResources& r, const JobPlan& plan, double timeOffset) {
    std::vector<nlohmann::json> records;
    for (uint32_t frame = 0; frame < r.scene.sequence.frames; ++frame)
        records.push_back(sequenceFrameRecord(r, sequenceRig(r, plan.width, plan.height, frame), plan.width,
                                              plan.height, frame, timeOffset,
                                              r.withVegetation() ? sceneColliders(r, frame) : std::vector<Collider>{}));
    return records;
}

// Everything that determines the dataset's bytes except the device (added once the device is open): see
// dataset/fingerprint.h. The scene's assets are hashed by content, so a changed grass map is a different dataset.
nlohmann::json jobFingerprint(const Scene& scene, const JobPlan& plan, const RenderJobOptions& options,
                              const std::vector<SceneAsset>& assets) {
    auto vec3 = [](const std::optional<glm::dvec3>& v) {
        return v ? nlohmann::json{v->x, v->y, v->z} : nlohmann::json(nullptr);
    };
    return {{"scene_sha256", sceneHash(options)},
            {"assets", assetHashes(assets)},
            {"seed", scene.seed},
            {"resolution", std::to_string(plan.width) + "x" + std::to_string(plan.height)},
            {"samples", plan.samples},
            {"no_vegetation", options.noVegetation},
            {"time", options.time},
            {"camera", vec3(options.cameraPosition)},
            {"look_at", vec3(options.cameraLookAt)},
            {"fov_y_deg", options.fovYDegrees ? nlohmann::json(*options.fovYDegrees) : nlohmann::json(nullptr)},
            {"sward_revision", SWARD_REVISION}};
}

// scene.json: the scene file's bytes; the built-in scene is the empty object; a scene given as text or with
// overrides (the Python module) is the document actually parsed, as sceneHash hashes it.
std::string sceneCopyText(const RenderJobOptions& options) {
    if (!sceneIsTheFile(options)) {
        SceneInput input = sceneInput(options);
        input.seed.reset();
        return sceneInputJson(input).dump(2) + "\n";
    }
    const std::string& scenePath = options.scenePath;
    if (scenePath.empty()) return "{}\n";
    return readInputFile(scenePath, "scene file", kMaxJsonFileBytes);
}

std::string classesText(const Scene& scene) {
    std::vector<std::string> names;
    for (uint32_t c = 0; c < scene.vegetation.categoryCount; ++c) names.push_back(scene.vegetation.categories[c].name);
    return classesFileText(names);
}

// The free space a run needs before it starts: one frame (an upper bound) and the per-dataset files.
uint64_t bytesNeeded(const DatasetWriter& dataset, const JobPlan& plan, const std::vector<nlohmann::json>& records,
                     uint64_t sceneBytes) {
    uint64_t sequenceBytes = sceneBytes;
    for (const nlohmann::json& record : records) sequenceBytes += record.dump().size() + 1;
    const uint64_t manifestBytes = uint64_t(plan.endFrame - plan.firstFrame + 1) * 12 * 128;
    constexpr uint64_t kSmallFiles = 4 * 8192; // calib.txt, dataset.json and the blocks of the two large ones
    return dataset.frameBytesUpperBound(plan.width, plan.height) + sequenceBytes + manifestBytes + kSmallFiles;
}

// A frame's range sensors, rendered with flow: the state its sweep sees and, in a world, the sweep itself.
struct FlowFrameSweep {
    RangeFrameState state;
    std::optional<std::vector<RangeScan>> scans;
};

// renderFrames with flow (render.flow): a frame's files need its neighbours' truth (dataset/flow_truth.h), so the
// frames render in order from the one before the first to write to the one after the last (those not to be written
// only for their truth), and frame f is written once f + 1 has rendered.
void renderFlowFrames(SceneGpu& gpu, OffscreenFrame& target, SceneResources& r, const JobPlan& plan,
                      const std::vector<uint32_t>& todo, DatasetWriter& dataset,
                      const std::optional<SensorModel>& sensor, const RenderJobOptions& options, BackgroundTask& writer,
                      Progress& progress, JobClock& clock, AutoExposure* autoExposure, RangeRecorder& range,
                      RutPatchCache& ruts) {
    if (todo.empty()) return; // a complete dataset
    const double baseline = r.scene.camera.rig.baseline;
    const std::set<uint32_t> toWrite(todo.begin(), todo.end());
    std::shared_ptr<const FrameImages> previous, current;
    std::shared_ptr<const RigCameras> currentCameras;
    std::shared_ptr<const FlowFrameSweep> currentSweep;
    uint32_t done = 0, started = 0;
    // From the frame before the first (its truth), or the first of its auto-exposure window (its meter).
    const uint32_t first = autoExposure ? autoExposure->framesToRender({todo.front()}).front() : todo.front();
    const uint32_t total = uint32_t(todo.size());
    for (uint32_t frame = std::min(first, todo.front() > 0 ? todo.front() - 1 : 0); frame <= todo.back() + 1; ++frame) {
        if (options.onProgress) options.onProgress(started, total);
        const double renderStart = clock.now();
        auto cameras = std::make_shared<RigCameras>();
        // The range sensors see the plants and ruts of the frame's own tick, as its cameras drew them, though its next
        // tick has run by the time it returns (rangeFlowFrameState).
        std::shared_ptr<const std::vector<GroundPatch>> patches;
        const bool sweep = range.active() && toWrite.contains(frame);
        auto images = std::make_shared<const FrameImages>(renderSequenceFrame(
            gpu, target, r, plan.width, plan.height, frame, options.time, sensor, *cameras, autoExposure,
            sweep ? std::function<void()>([&] { patches = rangeRutPatches(gpu, r, ruts); }) : nullptr));
        auto frameSweep = std::make_shared<FlowFrameSweep>();
        if (sweep) {
            frameSweep->state = rangeFlowFrameState(gpu, std::move(patches));
            // A world's sweeps cast against its resident tiles, which the next frame may evict: cast now.
            if (r.world) frameSweep->scans = range.sweep(frame, frameSweep->state.view(options.time));
        }
        if (current && toWrite.contains(frame - 1)) {
            RenderJobReport::Frame& t = clock.report.frames[started++]; // the render that completed its truth
            t.renderSeconds = clock.now() - renderStart;
            const double rendered = clock.now();
            writer.start([&dataset, &progress, &done, &clock, &t, &range, &options, baseline, frame, previous, current,
                          images, currentCameras, currentSweep] {
                clock.timeWrite(t, [&] {
                    const FlowNeighbours neighbours{frame - 1 > 0 ? previous.get() : nullptr, images.get()};
                    dataset.writeFrame(frame - 1, *current, currentCameras->left, baseline, &neighbours);
                    if (currentSweep->scans)
                        range.write(dataset, frame - 1, *currentSweep->scans);
                    else if (range.active())
                        range.record(dataset, frame - 1, currentSweep->state.view(options.time));
                });
                progress.frameDone(++done, frame - 1);
            });
            t.waitSeconds = clock.now() - rendered;
        }
        previous = std::exchange(current, images);
        currentCameras = cameras;
        currentSweep = std::move(frameSweep);
    }
    writer.wait();
    if (options.onProgress) options.onProgress(total, total);
}

// Renders and writes the frames of `todo` (in order). The simulation runs every tick from 0, so skipped frames
// and other shards' frames still leave their tracks.
void renderFrames(Context& ctx, SceneResources& r, const JobPlan& plan, const std::vector<uint32_t>& todo,
                  DatasetWriter& dataset, const std::optional<SensorModel>& sensor, const RenderJobOptions& options,
                  JobClock& clock) {
    RangeRecorder range(r); // before createSceneGpu releases the atlas
    RutPatchCache ruts;
    SceneGpu gpu = createSceneGpu(ctx, r, plan.samples, SimulationMode::WhenSceneHasColliders);
    const RigParams& rig = r.scene.camera.rig;
    OffscreenFrame target(ctx, plan.width, plan.height, plan.samples, r.scene.render.flow);
    Progress progress{!options.quiet && isatty(fileno(stderr)), uint32_t(todo.size())};
    uint32_t done = 0;
    // A frame's files are encoded and written while the next frame renders (the CPU driver's vertex stage runs on
    // one thread, and a GPU renders on its own). One frame at a time: start() waits for the previous frame's files,
    // so a write error stops the run one frame later at the most, and progress counts frames on disk.
    BackgroundTask writer;
    clock.report.setupSeconds = clock.now();
    clock.report.frames.resize(todo.size());
    // Auto-exposure: the W frames before each frame to write render too, for their meter (render/auto_exposure.h).
    std::optional<AutoExposure> autoExposure;
    if (sensor && sensor->params().autoExposure.enabled)
        autoExposure.emplace(sensor->params().autoExposure, r.scene.sequence.timeStep);
    AutoExposure* exposure = autoExposure ? &*autoExposure : nullptr;
    if (r.scene.render.flow) {
        renderFlowFrames(gpu, target, r, plan, todo, dataset, sensor, options, writer, progress, clock, exposure, range,
                         ruts);
        return;
    }
    size_t i = 0;
    for (const uint32_t frame : exposure ? exposure->framesToRender(todo) : todo) {
        if (options.onProgress) options.onProgress(uint32_t(i), uint32_t(todo.size()));
        if (frame != todo[i]) { // rendered for its meter alone: the window of a frame to write
            RigCameras cameras;
            renderSequenceFrame(gpu, target, r, plan.width, plan.height, frame, options.time, sensor, cameras,
                                exposure);
            continue;
        }
        RenderJobReport::Frame& t = clock.report.frames[i++];
        const double renderStart = clock.now();
        auto cameras = std::make_shared<RigCameras>();
        auto images = std::make_shared<const FrameImages>(renderSequenceFrame(
            gpu, target, r, plan.width, plan.height, frame, options.time, sensor, *cameras, exposure));
        auto state = std::make_shared<RangeFrameState>();
        if (range.active()) *state = rangeFrameState(gpu, r, ruts);
        // A world's sweeps cast against its resident tiles, which the next frame may evict: cast now, write later.
        auto scans = std::make_shared<std::optional<std::vector<RangeScan>>>();
        if (range.active() && r.world) *scans = range.sweep(frame, state->view(options.time));
        const double rendered = clock.now();
        t.renderSeconds = rendered - renderStart;
        writer.start([&dataset, &progress, &done, &rig, &range, &options, &clock, &t, frame, images, cameras, state,
                      scans] {
            clock.timeWrite(t, [&] {
                dataset.writeFrame(frame, *images, cameras->left, rig.baseline);
                if (*scans)
                    range.write(dataset, frame, **scans);
                else if (range.active())
                    range.record(dataset, frame, state->view(options.time));
            });
            progress.frameDone(++done, frame);
        });
        t.waitSeconds = clock.now() - rendered;
    }
    writer.wait();
    if (options.onProgress) options.onProgress(uint32_t(todo.size()), uint32_t(todo.size()));
}

// The manifest: everything needed to reproduce and verify the files, and nothing that changes between two runs of
// the same command (no dates, no timings), so identical datasets have identical manifests.
void writeJobManifest(DatasetWriter& dataset, const Scene& scene, const JobPlan& plan, const nlohmann::json& fingerprint,
                      const std::vector<SceneAsset>& assets, const RenderJobOptions& options) {
    std::vector<std::string> files = dataset.datasetFiles();
    for (uint32_t frame = plan.firstFrame; frame < plan.endFrame; ++frame)
        for (std::string& file : dataset.frameFiles(frame)) files.push_back(std::move(file));
    nlohmann::json jobOptions = {{"resolution", std::to_string(plan.width) + "x" + std::to_string(plan.height)},
                                 {"samples", plan.samples},
                                 {"no_vegetation", options.noVegetation},
                                 {"time", options.time}};
    if (options.cameraPosition || options.cameraLookAt || options.fovYDegrees) jobOptions["camera_override"] = true;
    nlohmann::json info = {{"format", "sward-dataset-1"},
                           {"scene", options.sceneText ? "<scene>" : options.scenePath.empty() ? "<built-in>" : options.scenePath},
                           {"scene_sha256", fingerprint["scene_sha256"]},
                           {"assets", assetManifest(assets, std::filesystem::path(options.scenePath).parent_path())},
                           {"units", datasetUnits()},
                           {"conventions", datasetConventions()},
                           {"seed", scene.seed},
                           {"frames", {plan.firstFrame, plan.endFrame}},
                           {"shard", options.shard ? nlohmann::json(*options.shard) : nlohmann::json(nullptr)},
                           {"options", jobOptions},
                           {"sward_revision", SWARD_REVISION},
                           {"device", fingerprint["device"]},
                           {"driver", fingerprint["driver"]},
                           {"fingerprint", fingerprint}};
    std::string manifest = options.shard ? shardManifestName(plan.shardIndex, plan.shardCount) : kManifestFile;
    dataset.writeManifest(manifest, info, files);
}

} // namespace

RenderJobReport runRenderJob(const RenderJobOptions& options) {
    JobClock clock;

    // One writer per folder: the shards of one run share the folder; --overwrite, or a run of the whole range,
    // must be alone in it. A folder another writer holds is refused before any work.
    const bool sharedWriter = options.shard && !options.overwrite;
    DatasetWriter::requireNoOtherWriter(options.outDir, sharedWriter);

    // Everything that can be checked without a GPU is checked first, so bad input fails fast and writes nothing.
    Scene scene = loadSceneInput(sceneInput(options));
    const JobPlan plan = planJob(scene, options);
    SceneResources resources = buildSceneResources(std::move(scene), !options.noVegetation);
    RigCameras firstRig;
    const std::optional<SensorModel> sensor =
        checkRigAndSensor(resources, plan.width, plan.height, plan.firstFrame, firstRig);
    const bool stereo = resources.scene.camera.rig.stereo();

    const std::vector<nlohmann::json> records = sequenceRecords(resources, plan, options.time);
    const bool motionBlur = sensor && sensor->params().shutterSeconds > 0.0; // the sub-frames' blur lengths
    const bool autoExposure = sensor && sensor->params().autoExposure.enabled; // auto_exposure/ per frame
    const uint32_t rawBitDepth = sensor ? sensor->params().bitDepth : 0; // raw/ per frame (scene/sensor_raw.h)
    DatasetWriter dataset(options.outDir, stereo, resources.scene.rangeSensors, resources.scene.render.flow,
                          motionBlur, autoExposure, rawBitDepth);
    std::vector<uint32_t> todo; // resume: frames whose files all exist are complete
    for (uint32_t frame = plan.firstFrame; frame < plan.endFrame; ++frame)
        if (options.overwrite || !dataset.frameComplete(frame)) todo.push_back(frame);
    const uint32_t skipped = (plan.endFrame - plan.firstFrame) - uint32_t(todo.size());
    const std::vector<SceneAsset> assets = sceneAssets(resources.scene);
    nlohmann::json fingerprint = jobFingerprint(resources.scene, plan, options, assets);
    const std::string sceneText = sceneCopyText(options);
    const uint64_t needed = todo.empty() ? 0 : bytesNeeded(dataset, plan, records, sceneText.size());
    dataset.check(fingerprint, options.overwrite, needed, sharedWriter); // before the device: a bad folder fails fast

    // From here on files are written; a failure removes what this run created (a kill leaves complete files only).
    try {
        dataset.lock(sharedWriter); // before the device, so a second writer fails at once
        Context ctx(DeviceOptions{.deviceFilter = options.device,
                                  .validation = options.validation || DeviceOptions{}.validation});
        fingerprint["device"] = ctx.device.name();
        clock.report.device = ctx.device.name();
        fingerprint["driver"] = ctx.device.driver();
        dataset.check(fingerprint, options.overwrite, needed, sharedWriter);
        dataset.begin(fingerprint, options.overwrite);
        const RigParams& rig = resources.scene.camera.rig;
        if (rig.stereo()) dataset.writeCalib(firstRig.left, rig.baseline, rig.minDepth);
        dataset.writeFrameLog(records);
        dataset.writeSceneFiles(sceneText, classesText(resources.scene));
        renderFrames(ctx, resources, plan, todo, dataset, sensor, options, clock);
        uint32_t messages = ctx.device.validationMessageCount();
        require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");
        const double manifestStart = clock.now();
        writeJobManifest(dataset, resources.scene, plan, fingerprint, assets, options);
        clock.report.manifestSeconds = clock.now() - manifestStart;
    } catch (...) {
        dataset.discardCreated();
        throw;
    }

    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.2f s", clock.now());
    clock.report.width = plan.width;
    clock.report.height = plan.height;
    clock.report.samples = plan.samples;
    clock.report.summary = resources.scene.name + ", frames " + std::to_string(plan.firstFrame) + ":" +
                           std::to_string(plan.endFrame) + " (" + std::to_string(todo.size()) + " rendered, " +
                           std::to_string(skipped) + " already complete), " + std::to_string(plan.width) + "x" +
                           std::to_string(plan.height) + ", " + std::to_string(plan.samples) + "x MSAA, " +
                           (stereo ? "stereo" : "mono") + " -> " + options.outDir + " in " + seconds;
    if (resources.world) { // what streaming did: a track kept across an eviction shows as a restored tile
        const WorldTileStats& w = resources.world->stats();
        clock.report.summary += "; world tiles: " + std::to_string(w.generated) + " generated (" +
                                std::to_string(w.restored) + " restored with kept state), " +
                                std::to_string(w.evicted) + " evicted";
    }
    return std::move(clock.report);
}

std::string datasetSceneText(const RenderJobOptions& options) {
    return sceneCopyText(options);
}

std::string datasetSceneHash(const RenderJobOptions& options) {
    return sceneHash(options);
}

std::string datasetClassesText(const Scene& scene) {
    return classesText(scene);
}

std::string datasetRevision() {
    return SWARD_REVISION;
}

void parseFrameRange(const std::string& text, uint32_t& first, uint32_t& end) {
    const auto [a, b] = parseHalfOpenRange(text, 0, kFrameLimit, "bad frame range");
    first = uint32_t(a);
    end = uint32_t(b);
}

} // namespace sward
