// sward-bench world: the CPU side of a world of many tiles — tile generation time and resident memory against the
// number of resident tiles, in a small and a large world. (The GPU half, upload and frame time against resident tiles,
// is the renderer's.)
#include "render/benchmarks.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "scene/world_tiles.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

namespace sward {

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double cpuMsSince(std::clock_t start) {
    return double(std::clock() - start) * 1000.0 / CLOCKS_PER_SEC;
}

double medianOf(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

// The scene with `tiles` x `tiles` tiles and a budget that never limits the figures (they measure, not refuse).
Scene sizedWorld(Scene scene, uint32_t tiles) {
    scene.world.tilesX = scene.world.tilesY = tiles;
    scene.world.memoryBudgetBytes = uint64_t(1) << 50;
    return scene;
}

// Tiles (0..k-1, 0..k-1) one by one: wall and process CPU time of each.
nlohmann::json generationFigures(const Scene& scene, uint32_t count, uint32_t threads) {
    std::vector<double> wall, cpu, plants;
    for (uint32_t i = 0; i < count; ++i) {
        const TileCoord coord{int32_t(i % scene.world.tilesX), int32_t(i / scene.world.tilesX)};
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpuStart = std::clock();
        const WorldTile tile = generateWorldTile(scene, coord, threads);
        wall.push_back(msSince(start));
        cpu.push_back(cpuMsSince(cpuStart));
        plants.push_back(double(countVegetation(tile.vegetation).plants));
    }
    const double ms = medianOf(wall), plantsPerTile = medianOf(plants);
    return {{"tiles", count},
            {"ms_per_tile", ms},
            {"cpu_ms_per_tile", medianOf(cpu)},
            {"plants_per_tile", plantsPerTile},
            {"plants_per_second", plantsPerTile / (ms / 1000.0)},
            {"runs_ms", wall}};
}

// Resident bytes with n tiles resident: one interest point at the centre of each tile of the k x k block at the
// south-west corner, load radius 1 m, so exactly those tiles load (in a world of at least k x k tiles).
nlohmann::json residentFigures(const Scene& base, uint32_t worldTiles, const std::vector<uint32_t>& counts,
                               uint32_t threads, uint64_t oneTile) {
    Scene scene = sizedWorld(base, worldTiles);
    scene.world.loadRadius = 1.0;
    scene.world.evictRadius = 2.0;
    nlohmann::json rows = nlohmann::json::array();
    for (uint32_t n : counts) {
        const uint32_t k = uint32_t(std::lround(std::sqrt(double(n))));
        if (k * k != n || k > worldTiles) continue;
        WorldTiles world(scene, threads);
        std::vector<glm::dvec2> points;
        const double s = scene.vegetation.tileSize;
        for (uint32_t y = 0; y < k; ++y)
            for (uint32_t x = 0; x < k; ++x)
                points.push_back(glm::dvec2(scene.vegetation.worldOrigin) + s * glm::dvec2(x + 0.5, y + 0.5));
        const auto start = std::chrono::steady_clock::now();
        world.waitFor(points);
        const double ms = msSince(start);
        rows.push_back({{"resident_tiles", world.residentCount()},
                        {"resident_bytes", world.residentBytes()},
                        {"bytes_per_tile", double(world.residentBytes()) / n},
                        {"ratio_to_n_times_one", double(world.residentBytes()) / (double(n) * double(oneTile))},
                        {"wait_ms", ms}});
    }
    return rows;
}

// One camera at the middle of the 4 x 4 world's extent, at the scene's own radii, in both worlds.
nlohmann::json sameRadiusFigures(const Scene& base, uint32_t threads) {
    nlohmann::json result;
    const glm::dvec2 point = glm::dvec2(base.vegetation.worldOrigin) + 2.0 * double(base.vegetation.tileSize);
    for (uint32_t tiles : {4u, 16u}) {
        WorldTiles world(sizedWorld(base, tiles), threads);
        world.waitFor(std::span(&point, 1));
        result[std::to_string(tiles) + "x" + std::to_string(tiles)] = {{"resident_tiles", world.residentCount()},
                                                                       {"resident_bytes", world.residentBytes()}};
    }
    result["load_radius"] = base.world.loadRadius;
    return result;
}

} // namespace

nlohmann::json benchWorld(const WorldBenchOptions& options) {
    const std::string path =
        options.scenePath.empty() ? std::string(SWARD_SOURCE_DIR "/examples/world.json") : options.scenePath;
    Scene scene = loadScene(path, std::nullopt, options.allowAssets);
    require(scene.world.enabled, path + ": sward-bench world needs a scene with a 'world'");
    if (options.densityMultiplier > 0.0f) scene.vegetation.densityMultiplier = options.densityMultiplier;
    const uint32_t threads = resolveThreadCount(options.threads);
    const Scene large = sizedWorld(scene, 16);
    const uint64_t oneTile = generateWorldTile(large, {0, 0}, threads).bytes;

    nlohmann::json memory;
    for (uint32_t tiles : {4u, 16u})
        memory[std::to_string(tiles) + "x" + std::to_string(tiles)] =
            residentFigures(scene, tiles, options.resident, threads, oneTile);
    return {{"scene", path},
            {"threads", threads},
            {"density_multiplier", scene.vegetation.densityMultiplier},
            {"tile_size", scene.vegetation.tileSize},
            {"generation", generationFigures(large, options.tiles, threads)},
            {"tile_bytes", oneTile},
            {"predicted_tile_bytes", predictedTileBytes(scene)},
            {"memory", memory},
            {"same_radius", sameRadiusFigures(scene, threads)}};
}

std::string worldTable(const nlohmann::json& result) {
    std::string table = "world  resident  resident MiB  MiB/tile  ratio to n x one  wait ms\n";
    char line[160];
    for (const auto& [world, rows] : result.at("memory").items())
        for (const nlohmann::json& r : rows) {
            std::snprintf(line, sizeof line, "%-6s %8u  %12.1f  %8.2f  %16.4f  %7.0f\n", world.c_str(),
                          r.at("resident_tiles").get<uint32_t>(), r.at("resident_bytes").get<double>() / 1048576.0,
                          r.at("bytes_per_tile").get<double>() / 1048576.0, r.at("ratio_to_n_times_one").get<double>(),
                          r.at("wait_ms").get<double>());
            table += line;
        }
    return table;
}

} // namespace sward
