#include "scene/world_horizon.h"

#include "common/error.h"
#include "scene/scene.h"

#include <cmath>
#include <vector>

namespace sward {

Heightfield horizonHeights(const Scene& scene) {
    require(scene.world.enabled && scene.terrain.source == TerrainParams::Source::Procedural,
            "horizonHeights: a world of the procedural terrain");
    const WorldParams& w = scene.world;
    const double spacing = horizonSpacing(scene), tile = scene.vegetation.tileSize;
    const glm::dvec2 origin(scene.vegetation.worldOrigin);
    const uint32_t columns = uint32_t(std::ceil(w.tilesX * tile / spacing - 1e-9)) + 1;
    const uint32_t rows = uint32_t(std::ceil(w.tilesY * tile / spacing - 1e-9)) + 1;
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
