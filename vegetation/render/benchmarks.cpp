#include "benchmarks.h"

#include "context.h"
#include "render_target.h"
#include "scene.h"
#include "scene_renderer.h"
#include "timestamps.h"
#include "vegetation_renderer.h"
#include "ground.h"
#include "placement.h"
#include "vegetation_buffers.h"

#include <algorithm>
#include <map>
#include <chrono>
#include <thread>

namespace sward {

namespace {
double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

} // namespace

nlohmann::json benchGenerate(const GenerateBenchOptions& options) {
    require(options.density > 0.0f && options.density <= 1000.0f, "--density must be in (0, 1000] plants per m^2");
    require(options.repeats >= 1, "--repeats must be at least 1");
    uint32_t threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());

    // A flat-out uniform grass tile: every plant costs the same, so plants/s is comparable between runs.
    VegetationParams params;
    params.tileSize = options.tileSize;
    params.categories[1].density = options.density;
    params.memoryBudgetBytes = uint64_t(8) << 30;
    validateVegetationParams(params, "sward-bench generate");
    GrassMap map(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    Ground ground(makeProceduralTerrain({.size = options.tileSize, .spacing = 2.0f, .seed = 1}));

    std::vector<double> runs;
    VegetationTile tile;
    for (uint32_t i = 0; i < options.repeats; ++i) {
        auto start = std::chrono::steady_clock::now();
        tile = generateTile(ground, map, params, TileCoord{0, 0}, threads);
        runs.push_back(secondsSince(start));
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
    Scene scene = loadScene(options.scenePath.empty() ? std::string(SWARD_SOURCE_DIR "/examples/meadow.json")
                                                      : options.scenePath);
    Heightfield terrain = buildTerrain(scene);
    VegetationTile tile = buildVegetation(scene, terrain);
    Atlas atlas = buildAtlas(scene);
    Camera camera = sceneCamera(scene, terrain, options.width, options.height);

    Context ctx(DeviceOptions{.deviceFilter = options.device, .quiet = true});
    SceneRenderer renderer(ctx, scene, terrain, options.samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                           &tile, &atlas);
    const uint64_t plantsTotal = countVegetation(tile).plants;
    tile = {};
    RenderTarget main(ctx, mainPassTargetDesc(options.width, options.height, options.samples));
    RenderTarget truth(ctx, truthPassTargetDesc(options.width, options.height));
    GpuTimers timers(ctx.device, 8);
    auto timed = [&](const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBuffer cmd = ctx.submitter.begin();
        timers.reset(cmd);
        record(cmd);
        ctx.submitter.wait(ctx.submitter.submit(cmd));
        return timers.read();
    };

    // Full frames: every pass, timed. The first frame warms up caches and pipelines and is not counted.
    std::map<std::string, std::vector<double>> passes;
    for (uint32_t i = 0; i <= options.frames; ++i) {
        auto times = timed([&](VkCommandBuffer cmd) { renderer.record(cmd, main, &truth, camera, 0.0, i, &timers); });
        if (i > 0)
            for (auto& [name, ms] : times) passes[name].push_back(ms);
    }
    VegetationRenderer& vegetation = *renderer.vegetation();
    BakedPlants baked = vegetation.bake(0);

    // Expansion overhead: expansion + main pass against the same main pass drawing the same quads from the
    // baked static buffer; interleaved so both see the same machine state.
    std::vector<double> dynamicMs, staticMs;
    for (uint32_t i = 0; i <= options.frames; ++i) {
        auto dyn = timed([&](VkCommandBuffer cmd) { renderer.recordMainOnly(cmd, main, camera, 0.0, i, &timers, nullptr); });
        auto fix = timed([&](VkCommandBuffer cmd) { renderer.recordMainOnly(cmd, main, camera, 0.0, i, &timers, &baked); });
        if (i == 0) continue;
        double d = 0.0, f = 0.0;
        for (auto& [name, ms] : dyn) d += ms;
        for (auto& [name, ms] : fix) f += ms;
        dynamicMs.push_back(d);
        staticMs.push_back(f);
    }
    gpu::ExpansionStats stats = baked.stats;
    vegetation.destroyBaked(baked);

    nlohmann::json passMs = nlohmann::json::object();
    for (auto& [name, values] : passes) passMs[name] = median(values);
    double expansionMs = median(passes["expansion"]);
    double frameMs = median(dynamicMs), staticFrameMs = median(staticMs);
    return {
        {"pass_ms", passMs},
        {"plants_drawn_per_lod", {stats.instances.x, stats.instances.y, stats.instances.z}},
        {"plants_considered", stats.info.z},
        {"plants_total", plantsTotal},
        {"clusters_visible", stats.info.x},
        {"clusters_total", vegetation.buffers().clusterCount},
        {"expansion_plants_per_second", expansionMs > 0.0 ? double(stats.info.z) / (expansionMs * 1e-3) : 0.0},
        {"frame_ms", frameMs},
        {"static_frame_ms", staticFrameMs},
        {"expansion_overhead_ratio", staticFrameMs > 0.0 ? frameMs / staticFrameMs : 0.0},
        {"device", ctx.device.name()},
        {"width", options.width},
        {"height", options.height},
        {"samples", options.samples},
        {"frames", options.frames},
    };
}

} // namespace sward
