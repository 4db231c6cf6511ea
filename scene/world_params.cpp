#include "scene/world_params.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/land_cover_params.h"
#include "scene/scene.h"
#include "scene/world_ground.h"
#include "vegetation/cover_map.h"
#include "vegetation/placement.h"

#include <algorithm>
#include <cmath>

#include <unistd.h>

namespace sward {

namespace {

std::string mib(double bytes) {
    return formatNumber(std::ceil(bytes / 1048576.0)) + " MiB";
}

// value / step is a whole number (within float rounding of the scene's numbers).
bool wholeMultiple(double value, double step) {
    const double k = std::floor(value / step + 0.5);
    return std::abs(k * step - value) <= 1e-6 * std::max(1.0, std::abs(value));
}

// Tiles of one row (dy from the centre's row band) touched by the disc: those whose span [i s, (i+1) s] lies within
// w = sqrt(r^2 - dy^2) of cx.
uint32_t tilesInRow(double cx, double halfWidth, double s) {
    const double first = std::ceil((cx - halfWidth) / s - 1.0), last = std::floor((cx + halfWidth) / s);
    return last >= first ? uint32_t(last - first + 1.0) : 0u;
}

} // namespace

uint64_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

WorldParams parseWorldParams(JsonReader r) {
    WorldParams w;
    w.enabled = true;
    const glm::uvec2 tiles = r.wholeVector<2>("tiles", glm::uvec2(w.tilesX, w.tilesY), 1, kMaxWorldTilesPerSide);
    w.tilesX = tiles.x;
    w.tilesY = tiles.y;
    w.loadRadius = r.number("load_radius", w.loadRadius, 1.0, kMaxLoadRadius);
    w.evictRadius = r.number("evict_radius", w.loadRadius + 100.0, 1.0, kMaxEvictRadius);
    if (!(w.evictRadius > w.loadRadius))
        r.fail(r.name("evict_radius") + " (" + formatNumber(w.evictRadius) + " m) must be larger than " +
               r.name("load_radius") + " (" + formatNumber(w.loadRadius) + " m)");
    w.viewDistance = r.number("view_distance", w.loadRadius, 1.0, kMaxLoadRadius);
    if (w.viewDistance > w.loadRadius)
        r.fail(r.name("view_distance") + " (" + formatNumber(w.viewDistance) + " m) must not exceed " +
               r.name("load_radius") + " (" + formatNumber(w.loadRadius) + " m): only resident tiles can be drawn");
    if (const nlohmann::json* horizon = r.raw("horizon"); horizon && horizon->is_boolean())
        w.horizon = horizon->get<bool>();
    else if (horizon && horizon->is_object()) {
        JsonReader h(*horizon, r.source(), r.childPath("horizon"));
        w.horizonSpacing = h.number("spacing", 0.0, 0.0, kMaxWorldExtent);
        if (h.has("spacing") && !(w.horizonSpacing > 0.0)) h.fail(h.name("spacing") + " must be positive");
        h.finish();
    } else if (horizon)
        r.fail(r.name("horizon") + " must be false, true or an object with 'spacing'");
    if (r.has("memory_budget_mib"))
        w.memoryBudgetBytes = uint64_t(r.number("memory_budget_mib", 0.0, 1.0, 1048576.0) * 1048576.0);
    // A budget the machine cannot hold bounds nothing: a 1 TiB world kept generating tiles (50 MB/s, no frame)
    // until the system ran out. Refused only, never lowered, so the machine never changes what a scene renders.
    const uint64_t physical = physicalMemoryBytes();
    if (physical > 0 && w.memoryBudgetBytes > physical)
        r.fail(r.name("memory_budget_mib") + " (" + std::to_string(w.memoryBudgetBytes >> 20) +
               " MiB) is more than this machine's memory (" + std::to_string(physical >> 20) + " MiB)");
    r.finish();
    return w;
}

double horizonSpacing(const Scene& scene) {
    const WorldParams& w = scene.world;
    if (w.horizonSpacing > 0.0) return w.horizonSpacing;
    const double spacing = worldLattice(scene).spacing; // the procedural terrain's or the DEM's
    const double cells = double(std::max(w.tilesX, w.tilesY)) * scene.vegetation.tileSize / spacing;
    return spacing * std::max(1.0, std::ceil(cells / kDefaultHorizonCells - 1e-9));
}

void checkWorldScene(const Scene& scene) {
    const std::string& source = scene.source;
    auto fail = [&](const std::string& message) { throw Error(source + ": " + message); };
    if (scene.terrain.source == TerrainParams::Source::Mesh)
        fail("'world' needs the procedural terrain or a DEM ('terrain.heightmap'): a world of 'terrain.mesh' is not "
             "supported yet");
    if (glm::uvec2 pixels; !scene.grassMapPath.empty()) worldGrassMapBound(scene, pixels); // whole pixels per tile
    if (!scene.landCover.file.empty()) worldLandCoverGrid(scene); // it covers the world in whole pixels per tile
    const ProceduralTerrainParams& t = scene.terrain.procedural;
    const VegetationParams& v = scene.vegetation;
    if (demWorld(scene))
        checkDemWorld(scene); // the DEM's lattice instead of the procedural terrain's
    else if (std::abs(double(v.tileSize) - t.size) > 1e-3)
        fail("in a world every tile has its own terrain: 'vegetation.tile_size' (" + formatNumber(v.tileSize) +
             " m) must equal 'terrain.size' (" + formatNumber(t.size) + " m)");
    if (!demWorld(scene) && !wholeMultiple(t.size, t.spacing))
        fail("in a world 'terrain.size' (" + formatNumber(t.size) +
             " m) must be a whole number of 'terrain.spacing' (" + formatNumber(t.spacing) +
             " m), so the tiles' terrain grids meet");
    if (!demWorld(scene) && (!wholeMultiple(v.worldOrigin.x, t.spacing) || !wholeMultiple(v.worldOrigin.y, t.spacing)))
        fail("in a world 'vegetation.world_origin' must be a whole multiple of 'terrain.spacing' (" +
             formatNumber(t.spacing) + " m), so the tiles' terrain grids lie on one lattice");
    const WorldParams& w = scene.world;
    const double extent = double(std::max(w.tilesX, w.tilesY)) * v.tileSize;
    if (extent > kMaxWorldExtent)
        fail("'world.tiles' times 'vegetation.tile_size' is " + formatNumber(extent) + " m, over the " +
             formatNumber(kMaxWorldExtent) + " m a world may span (plant positions are floats)");
    checkWorldBudget(scene);
    // The ring's vertices are the fine lattice's samples at every k-th vertex, so it meets the tiles' ground there.
    if (w.horizon && w.horizonSpacing > 0.0) {
        const double lattice = worldLattice(scene).spacing;
        if (!wholeMultiple(w.horizonSpacing, lattice))
            fail("'world.horizon.spacing' (" + formatNumber(w.horizonSpacing) + " m) must be a whole multiple of " +
                 (demWorld(scene) ? "the DEM's sample spacing (" : "'terrain.spacing' (") + formatNumber(lattice) +
                 " m): the horizon ring samples the terrain's lattice");
        if (extent / w.horizonSpacing > kMaxHeightfieldCells)
            fail("'world.horizon.spacing' (" + formatNumber(w.horizonSpacing) + " m) gives " +
                 formatNumber(std::ceil(extent / w.horizonSpacing)) + " horizon cells along the world, over " +
                 std::to_string(kMaxHeightfieldCells) + "; raise it");
    }
}

void checkWorldDrawable(const Scene& scene) {
    auto fail = [&](const std::string& message) { throw Error(scene.source + ": " + message); };
    const WorldParams& w = scene.world;
    // Ground is drawn out to view_distance, within which every tile is resident; plants dissolve at lod.far (+ half
    // the band), so nothing drawn depends on which tiles beyond it happen to be resident.
    if (double(scene.lod.farLimit) + 0.5 * scene.lod.band > w.viewDistance)
        fail("in a world 'lod.far' + half 'lod.band' (" + formatNumber(scene.lod.farLimit + 0.5f * scene.lod.band) +
             " m) must not exceed 'world.view_distance' (" + formatNumber(w.viewDistance) +
             " m, default 'world.load_radius'): plants are drawn only from resident tiles");
    // Vehicles, free colliders and objects follow paths over the world's lattice ground; gusts blow within
    // view_distance of the camera (scene/world_objects.h).
    // A range sensor's rays meet the tiles within its range (+ kPlantLean: plants lean out of their tile) of its origin,
    // which must be resident: within load_radius of its sweep's start, an interest point (range/range_recorder.h).
    for (size_t k = 0; k < scene.rangeSensors.size(); ++k) {
        const RangeSensorParams& s = scene.rangeSensors[k];
        const std::string name = "'range_sensors[" + std::to_string(k) + "]' ('" + s.name + "')";
        if (s.maxRange + kPlantLean > w.loadRadius)
            fail(name + ": its 'range' (" + formatNumber(s.maxRange) + " m) plus " + formatNumber(kPlantLean) +
                 " m must not exceed " +
                 "'world.load_radius' (" + formatNumber(w.loadRadius) + " m): its rays meet only resident tiles");
    }
}

uint64_t predictedTileBytes(const Scene& scene, bool farCover) {
    const VegetationParams& v = scene.vegetation;
    // The world's lattice: a DEM's samples, or the procedural terrain's.
    const double spacing = worldLattice(scene).spacing;
    const double vertices = std::pow(std::round(double(v.tileSize) / spacing) + 1.0, 2.0);
    const double fields = double(v.fieldsPerTile()) * v.fieldsPerTile();
    const double clusters = fields * v.clustersPerField() * v.clustersPerField();
    double plants = 0.0, coverTexels = 0.0;
    if (scene.vegetationEnabled) {
        // The meadow's intensities never exceed 1, a land cover's its table's largest (up to kMaxLandCoverIntensity), a
        // grass_map's its largest value per channel; rounding adds at most one plant per cluster and category.
        static const GrassMap full(1, 1, 3, {1.0f, 1.0f, 1.0f}, "full intensity");
        const bool landCover = !scene.landCover.file.empty(), grassMap = !scene.grassMapPath.empty();
        glm::uvec2 mapPixels(MeadowMapParams{}.resolution);
        const GrassMap bound = landCover  ? landCoverIntensityBound(scene.landCover)
                               : grassMap ? worldGrassMapBound(scene, mapPixels)
                                          : full;
        plants = predictPlantCount(bound, v) + clusters * v.categoryCount;
        if (landCover) mapPixels = worldLandCoverGrid(scene).pixelsPerTile;
        if (farCover) { // one per grass-map texel, in blocks beyond kMaxCoverMapEdge
            const glm::dvec2 pixels(mapPixels);
            const glm::dvec2 edges = glm::min(pixels, double(kMaxCoverMapEdge));
            coverTexels = edges.x * edges.y;
        }
    }
    const double bytes = vertices * sizeof(float) + coverTexels * sizeof(glm::vec4) +
                         plants * double(sizeof(gpu::PlantStatic) + sizeof(gpu::PlantDynamic)) +
                         clusters * double(sizeof(gpu::PlantCluster)) + fields * double(sizeof(FieldVegetation));
    return uint64_t(std::min(std::ceil(bytes), 1e18));
}

uint32_t maxTilesWithin(double radius, double tileSize, uint32_t tilesX, uint32_t tilesY) {
    constexpr uint32_t kSamples = 64;
    const double s = tileSize, r = radius + s / kSamples; // any centre lies within s / 64 of a sample
    uint64_t most = 0;
    for (uint32_t sy = 0; sy <= kSamples; ++sy) {
        for (uint32_t sx = 0; sx <= kSamples; ++sx) {
            const double cx = s * sx / kSamples, cy = s * sy / kSamples;
            uint64_t count = 0, rows = 0;
            // Rows below, in and above the centre's: row j spans [j s, (j + 1) s].
            const int64_t lo = int64_t(std::floor((cy - r) / s)), hi = int64_t(std::floor((cy + r) / s));
            for (int64_t j = lo; j <= hi && rows < tilesY; ++j) {
                const double dy = std::max({0.0, double(j) * s - cy, cy - double(j + 1) * s});
                if (dy > r) continue;
                count += std::min(tilesInRow(cx, std::sqrt(r * r - dy * dy), s), tilesX);
                ++rows;
            }
            most = std::max(most, count);
        }
    }
    return uint32_t(std::min<uint64_t>(most, uint64_t(tilesX) * tilesY));
}

void checkWorldBudget(const Scene& scene, bool farCover) {
    const WorldParams& w = scene.world;
    const uint32_t tiles = maxTilesWithin(w.evictRadius, scene.vegetation.tileSize, w.tilesX, w.tilesY);
    const uint64_t perTile = predictedTileBytes(scene, farCover);
    const double bytes = double(tiles) * double(perTile);
    require(bytes <= double(w.memoryBudgetBytes),
            scene.source + ": 'world.memory_budget_mib' (" + mib(double(w.memoryBudgetBytes)) +
                ") cannot hold the tiles around one camera: up to " + std::to_string(tiles) + " tiles of " +
                formatNumber(scene.vegetation.tileSize) + " m lie within 'world.evict_radius' (" +
                formatNumber(w.evictRadius) + " m; 'world.load_radius' " + formatNumber(w.loadRadius) +
                " m) of a point, each up to " + mib(double(perTile)) +
                (farCover ? " of terrain, plant records and far cover" : " of terrain and plant records") + "; raise 'world.memory_budget_mib' or lower 'world.load_radius' / "
                "'world.evict_radius' or 'vegetation.density_multiplier'");
}

} // namespace sward
