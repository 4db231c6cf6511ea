#include "benchmarks.h"

#include "context.h"
#include "ground.h"
#include "placement.h"
#include "vegetation_buffers.h"

#include <algorithm>
#include <chrono>
#include <thread>

namespace sward {

namespace {
double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

} // namespace sward
