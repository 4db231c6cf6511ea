// sward-bench world: a world of many tiles — tile generation time and resident memory against the number of resident
// tiles, in a small and a large world (CPU), and tile upload time and frame time against the number of resident
// tiles (GPU).
#include "render/benchmarks.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "common/statistics.h"
#include "common/stopwatch.h"
#include "engine/timestamps.h"
#include "io/sha256.h"
#include "render/scene_gpu.h"
#include "scene/scene_resources.h"
#include "scene/world_ground.h"
#include "scene/world_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sward {

namespace {

// The scene with `tiles` x `tiles` tiles and a budget that never limits the figures (they measure, not refuse).
Scene sizedWorld(Scene scene, uint32_t tiles) {
    scene.world.tilesX = scene.world.tilesY = tiles;
    scene.world.memoryBudgetBytes = uint64_t(1) << 50;
    return scene;
}

// Tiles (0..k-1, 0..k-1) one by one: wall and process CPU time of each. A GIS world's tiles read their DEM window
// and land-cover window: those reads (with the grass map made from the land cover) are timed apart as well, the
// same calls generateWorldTile makes, so the share of the raster reads in a tile's generation shows.
nlohmann::json generationFigures(const Scene& scene, uint32_t count, uint32_t threads) {
    std::vector<double> wall, cpu, plants, demMs, coverMs;
    const bool dem = demWorld(scene), landCover = !scene.landCover.file.empty();
    for (uint32_t i = 0; i < count; ++i) {
        const TileCoord coord{int32_t(i % scene.world.tilesX), int32_t(i / scene.world.tilesX)};
        const Stopwatch generation = Stopwatch::withCpuTime();
        const WorldTile tile = generateWorldTile(scene, coord, threads);
        wall.push_back(generation.ms());
        cpu.push_back(generation.cpuMs());
        plants.push_back(double(countVegetation(tile.vegetation).plants));
        const glm::dvec2 lo =
            glm::dvec2(scene.vegetation.worldOrigin) + double(scene.vegetation.tileSize) * glm::dvec2(coord.x, coord.y);
        if (dem) {
            const Stopwatch read;
            (void)worldTileHeights(scene, lo, lo + double(scene.vegetation.tileSize));
            demMs.push_back(read.ms());
        }
        if (landCover) {
            const Stopwatch read;
            (void)buildGrassMap(scene, scene.vegetation.tileSize, lo);
            coverMs.push_back(read.ms());
        }
    }
    const double ms = median(wall), plantsPerTile = median(plants);
    nlohmann::json figures = {{"tiles", count},
                              {"ms_per_tile", ms},
                              {"cpu_ms_per_tile", median(cpu)},
                              {"plants_per_tile", plantsPerTile},
                              {"plants_per_second", plantsPerTile / (ms / 1000.0)},
                              {"runs_ms", wall}};
    if (dem) figures["dem_window_ms_per_tile"] = median(demMs);
    if (landCover) figures["land_cover_grass_map_ms_per_tile"] = median(coverMs);
    return figures;
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
        const Stopwatch wait;
        world.waitFor(points);
        const double ms = wait.ms();
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

// Frame time against resident tiles: the camera stands at the centre of tile (0, 0), 2 m up, looking along +x; with
// view_distance = lod.far + half the band it sees that tile only, whatever else is resident. Tiles of the k x k block
// at the corner are made resident (k = 1, 2, 3, 4): the frames must stay bitwise the same (checked) and their cost
// shows what a resident tile out of sight costs. Upload: wall time of addTile per tile (terrain, plants, cover).
nlohmann::json gpuFigures(const Scene& base, const WorldBenchOptions& options, uint32_t threads) {
    Scene scene = sizedWorld(base, 4);
    // The GPU refuses a budget beyond its memory (render/scene_gpu.cpp): the scene's own, which 16 tiles fit.
    scene.world.memoryBudgetBytes = base.world.memoryBudgetBytes;
    scene.world.viewDistance = double(scene.lod.farLimit) + 0.5 * scene.lod.band;
    scene.world.loadRadius = scene.world.viewDistance; // each point makes its own tile resident, no neighbour
    scene.world.evictRadius = scene.world.loadRadius + 100.0;
    SceneResources r = buildSceneResources(scene, true, threads);
    Context ctx(DeviceOptions{.deviceFilter = options.device, .quiet = true});
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::None);
    const double s = scene.vegetation.tileSize;
    const glm::dvec3 eye(glm::dvec2(scene.vegetation.worldOrigin) + 0.5 * s, 0.0);
    const Ground ground = cameraGround(scene, 0.0);
    const double z = ground.height(glm::vec2(eye)) + 2.0;
    const Camera camera = Camera::lookAt(glm::dvec3(eye.x, eye.y, z), glm::dvec3(eye.x + 40.0, eye.y, z - 2.0),
                                         glm::dvec3(0, 0, 1), 60.0, options.width, options.height);
    OffscreenFrame target(ctx, options.width, options.height, 1);
    nlohmann::json rows = nlohmann::json::array();
    std::string firstHash;
    for (uint32_t k = 1; k <= 4; ++k) {
        std::vector<glm::dvec2> points;
        for (uint32_t y = 0; y < k; ++y)
            for (uint32_t x = 0; x < k; ++x)
                points.push_back(glm::dvec2(scene.vegetation.worldOrigin) + s * glm::dvec2(x + 0.5, y + 0.5));
        r.world->waitFor(points);
        const Stopwatch upload;
        const uint32_t uploaded = syncWorldTiles(*gpu.renderer, *r.world);
        const double uploadMs = upload.ms();
        std::vector<double> wall, cpu;
        std::string hash;
        for (uint32_t i = 0; i <= options.frames; ++i) { // frame 0 warms up and is not counted
            const Stopwatch frame = Stopwatch::withCpuTime();
            const FrameImages images = target.render(*gpu.renderer, camera, 0.0, i);
            if (i == 0) continue;
            wall.push_back(frame.ms());
            cpu.push_back(frame.cpuMs());
            hash = sha256Hex(std::string_view(reinterpret_cast<const char*>(images.rgbaHalf.data()),
                                              images.rgbaHalf.size() * sizeof(uint16_t)));
        }
        if (firstHash.empty()) firstHash = hash;
        rows.push_back({{"resident_tiles", gpu.renderer->tileCount()},
                        {"upload_ms_per_tile", uploaded ? uploadMs / uploaded : 0.0},
                        {"frame_ms", median(wall)},
                        {"frame_cpu_ms", median(cpu)},
                        {"same_image_as_one_tile", hash == firstHash}});
    }
    return {{"device", ctx.device.name()},
            {"resolution", std::to_string(options.width) + "x" + std::to_string(options.height)},
            {"frames", options.frames},
            {"view_distance", scene.world.viewDistance},
            {"rows", rows}};
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
            {"same_radius", sameRadiusFigures(scene, threads)},
            {"gpu", options.noGpu ? nlohmann::json(nullptr) : gpuFigures(scene, options, threads)}};
}

std::string worldTable(const nlohmann::json& result) {
    std::string table;
    char line[160];
    const nlohmann::json& g = result.at("generation");
    std::snprintf(line, sizeof line, "tile generation: %.1f ms (CPU %.1f ms), %.0f plants",
                  g.at("ms_per_tile").get<double>(), g.at("cpu_ms_per_tile").get<double>(),
                  g.at("plants_per_tile").get<double>());
    table += line;
    if (g.contains("dem_window_ms_per_tile")) {
        std::snprintf(line, sizeof line, ", of which the DEM window %.1f ms",
                      g.at("dem_window_ms_per_tile").get<double>());
        table += line;
    }
    if (g.contains("land_cover_grass_map_ms_per_tile")) {
        std::snprintf(line, sizeof line, ", the land cover's grass map %.1f ms",
                      g.at("land_cover_grass_map_ms_per_tile").get<double>());
        table += line;
    }
    table += "\nworld  resident  resident MiB  MiB/tile  ratio to n x one  wait ms\n";
    for (const auto& [world, rows] : result.at("memory").items())
        for (const nlohmann::json& r : rows) {
            std::snprintf(line, sizeof line, "%-6s %8u  %12.1f  %8.2f  %16.4f  %7.0f\n", world.c_str(),
                          r.at("resident_tiles").get<uint32_t>(), r.at("resident_bytes").get<double>() / 1048576.0,
                          r.at("bytes_per_tile").get<double>() / 1048576.0, r.at("ratio_to_n_times_one").get<double>(),
                          r.at("wait_ms").get<double>());
            table += line;
        }
    if (result.at("gpu").is_null()) return table;
    table += "resident  upload ms/tile  frame ms  frame CPU ms  same image\n";
    for (const nlohmann::json& r : result.at("gpu").at("rows")) {
        std::snprintf(line, sizeof line, "%8u  %14.1f  %8.1f  %12.1f  %s\n", r.at("resident_tiles").get<uint32_t>(),
                      r.at("upload_ms_per_tile").get<double>(), r.at("frame_ms").get<double>(),
                      r.at("frame_cpu_ms").get<double>(), r.at("same_image_as_one_tile").get<bool>() ? "yes" : "NO");
        table += line;
    }
    return table;
}

} // namespace sward
