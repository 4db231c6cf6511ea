#include "render/benchmarks.h"

#include "common/parallel_for.h"
#include "common/statistics.h"
#include "common/stopwatch.h"
#include "engine/context.h"
#include "engine/pipeline_statistics.h"
#include "engine/render_target.h"
#include "engine/resources.h"
#include "engine/timestamps.h"
#include "interaction/interaction.h"
#include "interaction/state_file.h"
#include "render/interaction_gpu.h"
#include "render/scene_gpu.h"
#include "render/vegetation_buffers.h"
#include "render/vegetation_renderer.h"
#include "scene/scene_resources.h"
#include "vegetation/placement.h"
#include "world/ground.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <thread>

namespace sward {

namespace {
nlohmann::json medians(const std::map<std::string, std::vector<double>>& series) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, values] : series) out[name] = median(values);
    return out;
}

// Uniform grass (every plant costs the same, so figures compare between runs) over a `tileSize` tile, independent
// of example files.
VegetationParams uniformGrassParams(float tileSize, float density, const char* what) {
    VegetationParams params;
    params.tileSize = tileSize;
    params.categories[1].density = density;
    params.memoryBudgetBytes = uint64_t(8) << 30;
    validateVegetationParams(params, what);
    return params;
}
const GrassMap& uniformGrassMap() {
    static const GrassMap map(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    return map;
}

// What a statistics-counting frame found: the plant draws' figures per pass and the plant pixels of the truth image.
struct PassCounts {
    std::vector<std::pair<std::string, DrawStatistics>> plants; // "shadow.near", ..., "main.far", ..., "truth.far"
    uint64_t coveredPixels = 0;

    // Sums of the ranges whose name starts with `prefix` ("main" or "main.far", ...).
    DrawStatistics sum(const std::string& prefix) const {
        DrawStatistics total;
        for (const auto& [name, s] : plants)
            if (name.compare(0, prefix.size(), prefix) == 0) {
                total.inputAssemblyPrimitives += s.inputAssemblyPrimitives;
                total.vertexInvocations += s.vertexInvocations;
                total.clippingPrimitives += s.clippingPrimitives;
                total.fragmentInvocations += s.fragmentInvocations;
            }
        return total;
    }
    uint64_t lanes(const std::string& pass) const { return sum(pass).fragmentInvocations; }
};

// Pixels whose ground-truth label is a plant (a vegetation category, felled or cut): where the nearest surface at the
// pixel centre is a plant, in the same 1-sample truth pass that writes the dataset's masks.
uint64_t plantPixels(const std::vector<uint8_t>& labelPairs) {
    uint64_t covered = 0;
    for (size_t i = 0; i + 8 <= labelPairs.size(); i += 8) {
        uint32_t label;
        std::memcpy(&label, &labelPairs[i], 4);
        const uint32_t semantic = label >> gpu::kInstanceBits;
        covered += (semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticVegetation + gpu::kMaxPlantCategories) ||
                   semantic == gpu::kSemanticFelled || semantic == gpu::kSemanticCut;
    }
    return covered;
}

// One timed frame in two submissions: the expansion, then the draw passes; with `statistics`, the plant draws are
// counted by pipeline statistics (lavapipe crashes on a statistics query in a command buffer that also dispatches
// compute). The queries only count, the images are those of one SceneRenderer::record(); but on lavapipe passes
// with queries active ran markedly slower (the shadow pass 2-3x), so a counted frame is never a timed one.
std::vector<std::pair<std::string, double>> timedFrame(Context& ctx, SceneRenderer& renderer, RenderTarget& main,
                                                       RenderTarget& truth, const Camera& camera, uint32_t frame,
                                                       GpuTimers& timers, PipelineStatistics* statistics,
                                                       PassCounts& counts) {
    const SceneRenderer::View view{&camera, &main, &truth};
    VkCommandBuffer cmd = ctx.submitter.begin();
    timers.reset(cmd);
    renderer.recordExpansion(cmd, {&view, 1}, 0.0, frame, &timers);
    ctx.submitter.wait(ctx.submitter.submit(cmd));
    std::vector<std::pair<std::string, double>> times = timers.read();

    cmd = ctx.submitter.begin();
    timers.reset(cmd);
    if (statistics) statistics->reset(cmd);
    renderer.vegetation()->setStatistics(statistics);
    renderer.recordViews(cmd, {&view, 1}, 0.0, frame, &timers, /* expand= */ false);
    renderer.vegetation()->setStatistics(nullptr);
    ctx.submitter.wait(ctx.submitter.submit(cmd));
    for (auto& pass : timers.read()) times.push_back(pass);
    if (!statistics) return times;
    counts.plants = statistics->read();
    counts.coveredPixels = plantPixels(truth.readback(1));
    return times;
}

// Per pass and per LOD of the pass: triangles in / after clipping and fragment-shader invocations of the plant draws,
// and (main, truth) invocations per plant pixel of the image.
nlohmann::json fragmentFigures(const PassCounts& counts) {
    auto figures = [&](const std::string& name, bool perPixel) {
        const DrawStatistics s = counts.sum(name);
        nlohmann::json out = {{"triangles", s.inputAssemblyPrimitives},
                              {"vertex_invocations", s.vertexInvocations},
                              {"triangles_after_clipping", s.clippingPrimitives},
                              {"fragment_invocations", s.fragmentInvocations}};
        if (perPixel)
            out["lanes_per_covered_pixel"] =
                counts.coveredPixels ? double(s.fragmentInvocations) / double(counts.coveredPixels) : 0.0;
        return out;
    };
    nlohmann::json out = nlohmann::json::object();
    for (const char* pass : {"shadow", "main", "truth"}) {
        const bool perPixel = std::string(pass) != "shadow";
        out[pass] = figures(pass, perPixel);
        for (const char* lod : {"near", "mid", "far", "blades"})
            out[pass][lod] = figures(std::string(pass) + "." + lod, perPixel);
    }
    return out;
}

// The images of the latest frame: resolved colour, truth depth bits, truth labels.
std::array<std::vector<uint8_t>, 3> frameImages(RenderTarget& main, RenderTarget& truth) {
    return {main.readback(0), truth.readback(0), truth.readback(1)};
}

// Pixels whose `bytes`-byte values differ between two images of the same size.
uint64_t differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, size_t bytes) {
    uint64_t n = 0;
    for (size_t i = 0; i + bytes <= std::min(a.size(), b.size()); i += bytes)
        n += std::memcmp(&a[i], &b[i], bytes) != 0;
    return n;
}

// A cut-out variant against whole quads, same run: its passes and plant draws, the ratios of main-pass lanes and
// time, and the pixels whose colour, depth bits or label differ from the whole-quad image.
nlohmann::json cutoutFigures(const PassCounts& counts, const std::map<std::string, std::vector<double>>& passes,
                             const std::array<std::vector<uint8_t>, 3>& images, const PassCounts& quadCounts,
                             const std::map<std::string, std::vector<double>>& quadPasses,
                             const std::array<std::vector<uint8_t>, 3>& quadImages) {
    const double mainMs = median(passes.at("main")), quadMainMs = median(quadPasses.at("main"));
    return {
        {"pass_ms", medians(passes)},
        {"plant_draws", fragmentFigures(counts)},
        {"covered_pixels", counts.coveredPixels},
        {"main_lanes_ratio", double(counts.lanes("main")) / double(std::max<uint64_t>(quadCounts.lanes("main"), 1))},
        {"main_ms_ratio", quadMainMs > 0.0 ? mainMs / quadMainMs : 0.0},
        {"pixels_differing", {{"colour", differingPixels(images[0], quadImages[0], 8)},
                              {"depth", differingPixels(images[1], quadImages[1], 4)},
                              {"label", differingPixels(images[2], quadImages[2], 8)}}},
    };
}

// The floor (FrameBenchOptions::floor) from one run's main-pass medians: with full plant shading, with the plants'
// constant-colour shader, and without plant draws; each plant figure is its pass minus the pass without plants.
nlohmann::json floorFigures(const std::map<std::string, std::vector<double>>& fullPasses,
                            const std::map<std::string, std::vector<double>>& floorPasses,
                            const std::map<std::string, std::vector<double>>& withoutPasses) {
    const double full = median(fullPasses.at("main")), floorMs = median(floorPasses.at("main")),
                 without = median(withoutPasses.at("main"));
    return {{"main_ms", full},
            {"floor_main_ms", floorMs},
            {"without_plants_main_ms", without},
            {"plant_ms", full - without},
            {"floor_plant_ms", floorMs - without},
            {"plant_to_floor", floorMs > without ? (full - without) / (floorMs - without) : 0.0}};
}

// Expansion overhead: expansion + main pass against the same main pass drawing the same quads from the baked static
// buffer, interleaved so both see the same machine state, one submission each. Returns the medians (ms) of the two
// over `frames` frames after a warm-up.
std::pair<double, double> expansionOverhead(Context& ctx, SceneRenderer& renderer, RenderTarget& main,
                                            const Camera& camera, const BakedPlants& baked, uint32_t frames,
                                            GpuTimers& timers) {
    auto timedMs = [&](uint32_t frame, const BakedPlants* plants) {
        VkCommandBuffer cmd = ctx.submitter.begin();
        timers.reset(cmd);
        renderer.recordMainOnly(cmd, main, camera, 0.0, frame, &timers, plants);
        ctx.submitter.wait(ctx.submitter.submit(cmd));
        double total = 0.0;
        for (const auto& [name, ms] : timers.read()) total += ms;
        return total;
    };
    std::vector<double> dynamicMs, staticMs;
    for (uint32_t i = 0; i <= frames; ++i) {
        const double d = timedMs(i, nullptr), f = timedMs(i, &baked);
        if (i == 0) continue;
        dynamicMs.push_back(d);
        staticMs.push_back(f);
    }
    return {median(dynamicMs), median(staticMs)};
}

} // namespace

nlohmann::json benchGenerate(const GenerateBenchOptions& options) {
    require(options.density > 0.0f && options.density <= 1000.0f, "--density must be in (0, 1000] plants per m^2");
    require(options.repeats >= 1, "--repeats must be at least 1");
    const uint32_t threads = resolveThreadCount(options.threads);
    const VegetationParams params = uniformGrassParams(options.tileSize, options.density, "sward-bench generate");
    const GrassMap& map = uniformGrassMap();
    Ground ground(makeProceduralTerrain({.size = options.tileSize, .spacing = 2.0f, .seed = 1}));

    std::vector<double> runs;
    VegetationTile tile;
    for (uint32_t i = 0; i < options.repeats; ++i) {
        const Stopwatch generation;
        tile = generateTile(ground, map, params, TileCoord{0, 0}, threads);
        runs.push_back(generation.seconds());
    }
    std::vector<double> sorted = runs;
    std::sort(sorted.begin(), sorted.end());
    double seconds = sorted[sorted.size() / 2];
    VegetationStats stats = countVegetation(tile);

    nlohmann::json result = {
        {"plants", stats.plants},
        {"seconds", seconds},
        {"runs_seconds", runs},
        {"plants_per_second", double(stats.plants) / seconds},
        {"static_bytes_per_plant", double(stats.staticBytes) / double(stats.plants)},
        {"dynamic_bytes_per_plant", double(stats.dynamicBytes) / double(stats.plants)},
        {"cluster_bytes_per_plant", double(stats.clusterBytes) / double(stats.plants)},
        {"threads", threads},
        {"density", options.density},
        {"tile_size", options.tileSize},
    };
    if (options.upload) {
        Context ctx(DeviceOptions{.deviceFilter = options.device, .quiet = true});
        VegetationBuffers buffers(ctx, tile);
        result["upload_seconds"] = buffers.uploadSeconds;
        result["device"] = ctx.device.name();
        result["total_seconds"] = seconds + buffers.uploadSeconds;
    }
    return result;
}

nlohmann::json benchFrame(const FrameBenchOptions& options) {
    require(options.frames >= 1, "--frames must be at least 1");
    require(options.samples == 1 || options.samples == 4, "--samples must be 1 or 4");
    SceneResources resources = buildSceneResources(
        loadScene(options.scenePath.empty() ? std::string(SWARD_SOURCE_DIR "/examples/meadow.json") : options.scenePath,
                  std::nullopt, options.allowAssets));
    require(resources.withVegetation(), "sward-bench frame: the scene has no vegetation");
    const uint64_t plantsTotal = countVegetation(*resources.tile).plants;
    Camera camera = sceneCamera(resources.scene, resources.terrain, options.width, options.height);

    Context ctx(DeviceOptions{.deviceFilter = options.device, .quiet = true});
    SceneGpu scene = createSceneGpu(ctx, resources, options.samples, SimulationMode::None);
    SceneRenderer& renderer = *scene.renderer;
    RenderTarget main(ctx, mainPassTargetDesc(options.width, options.height, options.samples));
    RenderTarget truth(ctx, truthPassTargetDesc(options.width, options.height));
    GpuTimers timers(ctx.device, 8);

    // Full frames: every pass, timed, with whole quads (variant 0), with each cut-out corner count, and with the
    // floor's two main-pass variants (plants drawn by a constant-colour shader; no plants), interleaved so all see the
    // same machine state. The first frame of each warms up caches and pipelines and is not timed; it is the one whose
    // plant draws are counted.
    VegetationRenderer& vegetation = *renderer.vegetation();
    using Shading = VegetationRenderer::MainShading;
    const Atlas atlas = options.cutoutCorners.empty() ? Atlas{} : buildAtlas(resources.scene); // createSceneGpu let go of it
    // The 3 LODs and the near blades of the one tile: per shadow cascade, main, truth.
    PipelineStatistics statistics(ctx.device, (gpu::kLodCount + 1) * (gpu::kMaxShadowCascades + 2));
    std::vector<std::pair<uint32_t, Shading>> variants = {{0, Shading::Full}};
    for (uint32_t corners : options.cutoutCorners) variants.push_back({corners, Shading::Full});
    if (options.floor) variants.insert(variants.end(), {{0, Shading::Floor}, {0, Shading::Off}});
    std::vector<PassCounts> counts(variants.size());
    std::vector<std::map<std::string, std::vector<double>>> passes(variants.size());
    std::vector<std::array<std::vector<uint8_t>, 3>> images(variants.size());
    // The whole frame of whole quads on the host: both submissions and their waits, and the process's CPU time beside
    // it (every thread: lavapipe's rasterisers too).
    std::vector<double> wholeFrameMs, wholeFrameCpuMs;
    for (uint32_t i = 0; i <= options.frames; ++i)
        for (size_t v = 0; v < variants.size(); ++v) {
            vegetation.setCutout(variants[v].first, atlas);
            vegetation.setMainShading(variants[v].second);
            const Stopwatch frame = Stopwatch::withCpuTime();
            auto times = timedFrame(ctx, renderer, main, truth, camera, i, timers, i == 0 ? &statistics : nullptr,
                                    counts[v]);
            if (i > 0 && v == 0) {
                wholeFrameMs.push_back(frame.ms());
                wholeFrameCpuMs.push_back(frame.cpuMs());
            }
            if (i > 0)
                for (auto& [name, ms] : times) passes[v][name].push_back(ms);
            if (i == options.frames) images[v] = frameImages(main, truth);
        }
    vegetation.setCutout(0, atlas);
    vegetation.setMainShading(Shading::Full);
    nlohmann::json cutouts = nlohmann::json::object();
    for (size_t v = 1; v <= options.cutoutCorners.size(); ++v)
        cutouts[std::to_string(variants[v].first)] =
            cutoutFigures(counts[v], passes[v], images[v], counts[0], passes[0], images[0]);
    const nlohmann::json floor =
        options.floor ? floorFigures(passes[0], passes[variants.size() - 2], passes.back()) : nlohmann::json::object();
    BakedPlants baked = vegetation.bake(0);
    const auto [frameMs, staticFrameMs] = expansionOverhead(ctx, renderer, main, camera, baked, options.frames, timers);
    gpu::ExpansionStats stats = baked.stats;
    vegetation.destroyBaked(baked);

    double expansionMs = median(passes[0].at("expansion"));
    return {
        {"pass_ms", medians(passes[0])},
        {"whole_frame_ms", median(wholeFrameMs)},
        {"whole_frame_cpu_ms", median(wholeFrameCpuMs)},
        {"plants_drawn_per_lod", {stats.instances.x, stats.instances.y, stats.instances.z}},
        {"plants_considered", stats.info.z},
        {"plants_total", plantsTotal},
        {"clusters_visible", stats.info.x},
        {"clusters_total", vegetation.buffers().clusterCount},
        {"expansion_plants_per_second", expansionMs > 0.0 ? double(stats.info.z) / (expansionMs * 1e-3) : 0.0},
        {"frame_ms", frameMs},
        // The static baseline draws every baked triangle with the cards' shader: with near blades (drawn opaque by
        // their own pipeline in the frame) the two frames are not the same work, so no ratio.
        {"static_frame_ms", staticFrameMs},
        {"expansion_overhead_ratio", staticFrameMs > 0.0 && resources.scene.lod.nearBlades == 0
                                         ? nlohmann::json(frameMs / staticFrameMs)
                                         : nlohmann::json(nullptr)},
        {"plant_draws", fragmentFigures(counts[0])},
        {"covered_pixels", counts[0].coveredPixels},
        {"covered_fraction", double(counts[0].coveredPixels) / (double(options.width) * options.height)},
        {"cutout", cutouts},
        {"floor", floor},
        {"device", ctx.device.name()},
        {"width", options.width},
        {"height", options.height},
        {"samples", options.samples},
        {"frames", options.frames},
    };
}

namespace {

// FNV-1a 64 of a vector's bytes.
template <class T> uint64_t bytesHash(const std::vector<T>& values) {
    return fnv1a64(bytesOf(values));
}

// One measured tick of benchCollide.
struct CollideTick {
    double cpuMs = 0.0, cpuTimeMs = 0.0, binningMs = 0.0, mergeMs = 0.0, uploadMs = 0.0, gpuMs = 0.0;
    uint64_t uploadBytes = 0, dispatches = 0, contactsHash = 0;
    size_t contacts = 0, activeFields = 0;
    double total() const { return cpuMs + uploadMs + gpuMs; }
};

// One pushing sphere per cluster of the first `fields` fields, each circling 0.5 m around its cluster's centre at
// its own phase, so the set of touched plants changes every tick. Ids in cluster order.
std::vector<Collider> circlingSpheres(const VegetationTile& tile, uint32_t fields, float radius, uint64_t tick) {
    std::vector<Collider> colliders;
    const uint32_t perSide = tile.clustersPerField;
    for (uint32_t f = 0; f < fields; ++f)
        for (uint32_t k = 0; k < perSide * perSide; ++k) {
            const uint32_t id = f * perSide * perSide + k;
            const float angle = 0.05f * float(tick) + 0.7f * float(id);
            glm::vec2 centre = tile.fields[f].origin +
                               tile.clusterSize * (glm::vec2(float(k % perSide), float(k / perSide)) + 0.5f) +
                               0.5f * glm::vec2(std::cos(angle), std::sin(angle));
            // Low, like a wheel or a foot: the lower part of the sphere sinks into the ground.
            colliders.push_back(makeSphere(id, {centre, 0.6f * radius}, radius, 0.4f));
        }
    return colliders;
}


// The collision benchmark's fixture: a synthetic flat 500 x 500 m tile (20 x 20 fields of 5 x 5 clusters) and,
// with --gpu, the GPU side of the interaction. Without the GPU side the collision pass runs back to back, its
// working set warm in the caches; with it on lavapipe, the recovery pass (itself on the CPU) evicts them.
class CollideBench {
public:
    explicit CollideBench(const CollideBenchOptions& options)
        : threads(resolveThreadCount(options.threads)),
          params(uniformGrassParams(500.0f, options.density, "sward-bench collide")), tile(flatTile(params, threads)) {
        require(tile.fields.size() == 400, "sward-bench collide: the synthetic tile must have 400 fields");
        if (!options.gpu) return;
        ctx = std::make_unique<Context>(DeviceOptions{.deviceFilter = options.device, .quiet = true});
        buffers = std::make_unique<VegetationBuffers>(*ctx, tile);
        gpu = std::make_unique<InteractionGpu>(*ctx, *buffers);
        timers = std::make_unique<GpuTimers>(ctx->device, 4);
    }

    InteractionWorld newWorld() {
        InteractionWorld world(tile, params, interaction, threads);
        if (gpu) gpu->writeDynamics(world.initialDynamics());
        return world;
    }

    // Collision on the CPU (wall clock and CPU time around the whole step), then the GPU update in its own
    // submission, timed with GPU timestamps; the upload is the contact and range writes into host-visible memory.
    CollideTick runTick(InteractionWorld& world, std::span<const Collider> colliders) {
        CollideTick t;
        const Stopwatch step = Stopwatch::withCpuTime();
        TickResult r = world.step(colliders);
        t.cpuMs = step.ms();
        t.cpuTimeMs = step.cpuMs();
        t.binningMs = r.stats.buildMs;
        t.mergeMs = r.stats.mergeMs;
        t.contacts = r.contacts.size();
        t.contactsHash = bytesHash(r.contacts.flatten()); // after the timing: flattening copies
        t.activeFields = r.activeFields.size();
        if (!gpu) return t;
        const InteractionGpuStats before = gpu->stats();
        VkCommandBuffer cmd = ctx->submitter.begin();
        timers->reset(cmd);
        gpu->record(cmd, r.contacts, r.activeFields, interaction.recovery, uint32_t(r.tick), timers.get());
        ctx->submitter.wait(ctx->submitter.submit(cmd));
        for (auto& [name, ms] : timers->read()) t.gpuMs += ms;
        t.uploadBytes = gpu->stats().uploadBytes - before.uploadBytes;
        t.uploadMs = gpu->stats().uploadMs - before.uploadMs;
        t.dispatches = gpu->stats().dispatches - before.dispatches;
        return t;
    }

    const uint32_t threads;
    const VegetationParams params;
    const VegetationTile tile;
    const InteractionParams interaction;
    std::unique_ptr<Context> ctx;
    std::unique_ptr<VegetationBuffers> buffers;
    std::unique_ptr<InteractionGpu> gpu;
    std::unique_ptr<GpuTimers> timers;

private:
    static VegetationTile flatTile(const VegetationParams& params, uint32_t threads) {
        const uint32_t columns = uint32_t(params.tileSize / 2.0f) + 1;
        Ground ground(Heightfield(columns, columns, 2.0f, glm::vec2(0.0f),
                                  std::vector<float>(size_t(columns) * columns, 0.0f)));
        return generateTile(ground, uniformGrassMap(), params, TileCoord{0, 0}, threads);
    }
};

template <class Figure> double medianOf(const std::vector<CollideTick>& ticks, Figure figure) {
    std::vector<double> values;
    for (const CollideTick& t : ticks) values.push_back(double(figure(t)));
    return median(values);
}

// `warmup` + `ticks` ticks with spheres circling in the first `fields` fields; medians of the measured ticks.
nlohmann::json measureFields(CollideBench& bench, InteractionWorld& world, uint32_t fields, const CollideBenchOptions& options) {
    std::vector<CollideTick> measured;
    std::vector<Collider> colliders;
    std::vector<uint64_t> hashes; // of every tick's contacts, warm-up included: a check that they never change
    // Paced, the threads sleep between ticks as they do in a real-time loop, and each tick pays for waking them.
    const auto start = std::chrono::steady_clock::now();
    const std::chrono::duration<double> period(options.tickRate > 0.0 ? 1.0 / options.tickRate : 0.0);
    for (uint32_t i = 0; i < options.warmup + options.ticks; ++i) {
        if (options.tickRate > 0.0)
            std::this_thread::sleep_until(start +
                                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(i * period));
        colliders = circlingSpheres(bench.tile, fields, options.radius, world.tick());
        CollideTick t = bench.runTick(world, colliders);
        hashes.push_back(t.contactsHash);
        if (i >= options.warmup) measured.push_back(t);
    }
    return {
        {"fields", fields},
        {"colliders", colliders.size()},
        {"contacts", uint64_t(medianOf(measured, [](const CollideTick& t) { return t.contacts; }))},
        {"contacts_fnv1a", bytesHash(hashes)},
        {"active_fields", uint64_t(medianOf(measured, [](const CollideTick& t) { return t.activeFields; }))},
        {"cpu_collision_ms", medianOf(measured, [](const CollideTick& t) { return t.cpuMs; })},
        {"cpu_collision_cpu_time_ms", medianOf(measured, [](const CollideTick& t) { return t.cpuTimeMs; })},
        // The pass's two steps on the calling thread alone (the rest runs on every thread).
        {"cpu_collision_binning_ms", medianOf(measured, [](const CollideTick& t) { return t.binningMs; })},
        {"cpu_collision_merge_ms", medianOf(measured, [](const CollideTick& t) { return t.mergeMs; })},
        {"upload_bytes", uint64_t(medianOf(measured, [](const CollideTick& t) { return t.uploadBytes; }))},
        {"upload_ms", medianOf(measured, [](const CollideTick& t) { return t.uploadMs; })},
        {"gpu_recovery_ms", medianOf(measured, [](const CollideTick& t) { return t.gpuMs; })},
        {"gpu_recovery_ms_per_field",
         medianOf(measured,
                  [](const CollideTick& t) { return t.activeFields ? t.gpuMs / double(t.activeFields) : 0.0; })},
        {"total_ms", medianOf(measured, [](const CollideTick& t) { return t.total(); })},
    };
}

// The colliders leave: the touched fields recover and turn inactive, and from then on no tick may record any GPU
// work. Returns the dispatches counted over `ticks` idle ticks (must be 0).
uint64_t dispatchesOnceRecovered(CollideBench& bench, InteractionWorld& world, uint32_t ticks) {
    for (uint32_t i = 0; i <= bench.interaction.recovery.restTicks && !world.activeFields().empty(); ++i)
        bench.runTick(world, {});
    require(world.activeFields().empty(), "sward-bench collide: fields did not turn inactive after recovery");
    uint64_t dispatches = 0;
    for (uint32_t i = 0; i < ticks; ++i) dispatches += bench.runTick(world, {}).dispatches;
    return dispatches;
}

// 10,000 colliders hovering 50 m above the grass (drones, birds, a whole fleet parked high): they must cost next
// to nothing, and no field may become active. Returns the median tick time.
double idleCollidersMs(CollideBench& bench, const CollideBenchOptions& options, std::vector<Collider>& idle) {
    for (uint32_t i = 0; i < 10000; ++i)
        idle.push_back(makeSphere(i, {5.0f * float(i % 100) + 2.5f, 5.0f * float(i / 100) + 2.5f, 50.0f}, 0.5f, 1.0f));
    InteractionWorld world = bench.newWorld();
    std::vector<CollideTick> idleTicks;
    for (uint32_t i = 0; i < options.warmup + options.ticks; ++i) {
        CollideTick t = bench.runTick(world, idle);
        require(t.activeFields == 0 && t.dispatches == 0, "sward-bench collide: colliders above the grass touched it");
        if (i >= options.warmup) idleTicks.push_back(t);
    }
    return medianOf(idleTicks, [](const CollideTick& t) { return t.total(); });
}

} // namespace

nlohmann::json benchCollide(const CollideBenchOptions& options) {
    require(!options.fields.empty(), "--fields needs at least one value");
    for (uint32_t n : options.fields) require(n >= 1 && n <= 400, "--fields must be in [1, 400] (a 500 x 500 m tile)");
    require(options.ticks >= 1, "--ticks must be at least 1");
    require(options.density > 0.0f && options.density <= 1000.0f, "--density must be in (0, 1000] plants per m^2");
    require(options.radius > 0.0f && options.radius <= 2.0f, "--radius must be in (0, 2] metres");
    require(options.tickRate >= 0.0 && options.tickRate <= 1000.0, "--tick-rate must be in [0, 1000] ticks per second");
    CollideBench bench(options);

    nlohmann::json results = nlohmann::json::array();
    uint64_t zeroActiveDispatches = 0;
    for (size_t c = 0; c < options.fields.size(); ++c) {
        InteractionWorld world = bench.newWorld();
        results.push_back(measureFields(bench, world, options.fields[c], options));
        if (c == 0) zeroActiveDispatches = dispatchesOnceRecovered(bench, world, options.ticks);
    }
    std::vector<Collider> idle;
    const double idleMs = idleCollidersMs(bench, options, idle);
    return {
        {"results", results},
        {"idle_colliders", idle.size()},
        {"idle_colliders_ms", idleMs},
        {"zero_active_recovery_dispatches", zeroActiveDispatches},
        {"zero_active_ticks", options.ticks},
        {"plants", countVegetation(bench.tile).plants},
        {"density", options.density},
        {"radius", options.radius},
        {"tick_rate", options.tickRate},
        {"threads", bench.threads},
        {"ticks", options.ticks},
        {"device", bench.ctx ? bench.ctx->device.name() : std::string("none (--no-gpu)")},
    };
}

std::string collideTable(const nlohmann::json& result) {
    std::string out = "fields  colliders  contacts  cpu_collision_ms  (cpu time)  (binning, merge)  upload_bytes  "
                      "upload_ms  gpu_recovery_ms  gpu_ms_per_field  total_ms  contacts_fnv1a\n";
    char line[256];
    for (const nlohmann::json& r : result.at("results")) {
        std::snprintf(line, sizeof(line),
                      "%6u  %9u  %8.0f  %16.3f  %10.3f  %7.3f, %7.3f  %12.0f  %9.3f  %15.3f  %16.4f  %8.3f  %016llx\n",
                      r.at("fields").get<uint32_t>(), r.at("colliders").get<uint32_t>(),
                      double(r.at("contacts").get<uint64_t>()), r.at("cpu_collision_ms").get<double>(),
                      r.at("cpu_collision_cpu_time_ms").get<double>(), r.at("cpu_collision_binning_ms").get<double>(),
                      r.at("cpu_collision_merge_ms").get<double>(), double(r.at("upload_bytes").get<uint64_t>()),
                      r.at("upload_ms").get<double>(), r.at("gpu_recovery_ms").get<double>(),
                      r.at("gpu_recovery_ms_per_field").get<double>(), r.at("total_ms").get<double>(),
                      (unsigned long long)r.at("contacts_fnv1a").get<uint64_t>());
        out += line;
    }
    return out;
}

} // namespace sward
