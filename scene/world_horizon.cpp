#include "scene/world_horizon.h"

#include "common/error.h"
#include "io/raster_file.h"
#include "scene/scene.h"
#include "scene/world_ground.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sward {

namespace {

// The DEM's samples (i0 + k i, j0 + k j) for i < columns, j < rows (lattice indices from the DEM's south-west sample),
// in one read of every k-th sample, row-major from the south, as demSamples computes a tile's heights.
std::vector<float> demHorizon(const Scene& scene, glm::i64vec2 first, int64_t k, uint32_t columns, uint32_t rows) {
    const HeightmapParams& h = scene.terrain.heightmap;
    const int64_t northRow = int64_t(h.rows) - 1 - (first.y + k * (rows - 1)); // raster rows run north to south
    RasterBand raster;
    try {
        raster = readRasterWindow(h.path,
                                  {.column = uint32_t(first.x),
                                   .row = uint32_t(northRow),
                                   .width = columns,
                                   .height = rows,
                                   .step = uint32_t(k)},
                                  {.folders = scene.assets.folders()});
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.heightmap' (the horizon ring): " + e.what());
    }
    const float scale = float(h.heightScale), offset = float(h.heightOffset);
    std::vector<float> heights(size_t(columns) * rows);
    for (uint32_t row = 0; row < rows; ++row)
        for (uint32_t i = 0; i < columns; ++i) {
            const double value = raster.at(i, row);
            const float height = float(value) * scale + offset;
            if (raster.isNodata(value) || !std::isfinite(value) || !(std::abs(height) <= 1e6f))
                throw Error(scene.source + ": 'terrain.heightmap' ('" + h.path + "') has a nodata, non-finite or " +
                            "beyond 1e6 m sample at pixel (" + std::to_string(first.x + k * i) + ", " +
                            std::to_string(northRow + k * row) + "), which the world's horizon ring reads; fill the " +
                            "DEM first or set 'world.horizon' to false");
            heights[size_t(rows - 1 - row) * columns + i] = height;
        }
    return heights;
}

} // namespace

Heightfield horizonHeights(const Scene& scene) {
    const bool dem = demWorld(scene);
    require(scene.world.enabled && (dem || scene.terrain.source == TerrainParams::Source::Procedural),
            "horizonHeights: a world of the procedural terrain or a DEM");
    const WorldParams& w = scene.world;
    const double spacing = horizonSpacing(scene), tile = scene.vegetation.tileSize;
    const glm::dvec2 origin(scene.vegetation.worldOrigin);
    uint32_t columns = uint32_t(std::ceil(w.tilesX * tile / spacing - 1e-9)) + 1;
    uint32_t rows = uint32_t(std::ceil(w.tilesY * tile / spacing - 1e-9)) + 1;
    if (dem) {
        const WorldLattice lattice = worldLattice(scene);
        const int64_t k = std::llround(spacing / lattice.spacing);
        const glm::i64vec2 first(glm::round((origin - lattice.origin) / lattice.spacing));
        columns = std::min<uint32_t>(columns, uint32_t((int64_t(lattice.samples.x) - 1 - first.x) / k + 1));
        rows = std::min<uint32_t>(rows, uint32_t((int64_t(lattice.samples.y) - 1 - first.y) / k + 1));
        return Heightfield(columns, rows, float(spacing), glm::vec2(origin),
                           demHorizon(scene, first, k, columns, rows));
    }
    // Each sample from a one-cell window of the terrain whose south-west vertex is that lattice point: the very code
    // and lattice index a tile evaluates it with, so the heights agree bitwise whatever the two spacings round to.
    ProceduralTerrainParams window = scene.terrain.procedural;
    window.size = window.spacing;
    std::vector<float> heights(size_t(columns) * rows);
    for (uint32_t j = 0; j < rows; ++j)
        for (uint32_t i = 0; i < columns; ++i) {
            window.origin = origin + spacing * glm::dvec2(i, j);
            heights[size_t(j) * columns + i] = makeProceduralTerrain(window).sample(0, 0);
        }
    return Heightfield(columns, rows, float(spacing), glm::vec2(origin), std::move(heights));
}

} // namespace sward
