// The ground of a world (the scene's "world" key): one place that answers "the terrain heights over a window of the
// world's lattice", for the procedural terrain and for a DEM (terrain.heightmap, a GDAL raster read window by window,
// possibly far larger than memory). Tiles (generateWorldTile), the cameras' ground (cameraGround) and the actors'
// (latticeGround) all take their heights here, so they stand on bitwise the same surface whichever tiles are
// resident, and neighbouring tiles share their edge samples.
#pragma once

#include "world/heightfield.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <utility>

namespace sward {

struct Scene;

// The world's lattice: sample (i, j) lies at origin + spacing * (i, j) (x east, j north). The procedural terrain's:
// origin 0, spacing terrain.spacing, unbounded. A DEM's: origin terrain.heightmap.origin (its south-west sample),
// spacing its sample spacing in metres, samples its columns and rows.
struct WorldLattice {
    glm::dvec2 origin{0.0};
    double spacing = 1.0;
    glm::uvec2 samples{0u}; // a DEM's columns and rows; 0: the unbounded procedural lattice
    bool bounded() const { return samples.x > 0; }
    glm::dvec2 last() const { return origin + spacing * glm::dvec2(samples - 1u); } // a DEM's north-east sample
};

// True for a world whose ground is a DEM (world and terrain.heightmap).
bool demWorld(const Scene& scene);

// The lattice of a world scene's ground. Requires scene.world.enabled (a DEM world: fitWorldToDem has run).
WorldLattice worldLattice(const Scene& scene);

// The world's heights over [lo, hi], corners on the lattice (within 1e-6 relative), lo < hi: a heightfield of
// (hi - lo) / spacing + 1 samples a side whose sample (i, j) is the lattice's sample at lo + spacing * (i, j),
// bitwise whichever window it is read in. A DEM's heights are the raster's values times height_scale plus
// height_offset (as loadHeightfield computes them). Throws sward::Error naming the scene, 'terrain.heightmap' and
// the file for a window off the lattice or beyond the DEM, and for a nodata or non-finite sample inside the window,
// naming its world position, its pixel and the tile holding it (a world's DEM is not filled: a hole is an error).
Heightfield worldHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi);

// worldHeights of a tile's square with a one-sample skirt (HeightfieldSkirt) where the lattice goes on (always for
// the procedural terrain; a DEM's edge, or a side holding a nodata sample, has none): its edge vertices' normals are
// central differences, bitwise those of the neighbouring tile's edge.
Heightfield worldTileHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi);

// Bounds of every height of the world's tiles, the same whichever are resident: the procedural terrain's
// +-amplitude / 2; a DEM's smallest and largest height over the world's tiles (read strip by strip).
std::pair<float, float> worldHeightRange(const Scene& scene);

// At parse time, for a world on terrain.heightmap: reads the DEM's header (its size and spacing into
// terrain.heightmap.columns / rows / spacing), defaults vegetation.world_origin to the DEM's south-west sample and,
// unless `tilesGiven`, world.tiles to the DEM's extent in whole tiles. Throws sward::Error naming the scene and the
// keys for a PNG / EXR heightmap (read whole, never by windows), a DEM in degrees or without georeferencing and no
// metres_per_pixel, fewer than 2 x 2 samples, a DEM smaller than one tile, or more than kMaxWorldTilesPerSide tiles.
void fitWorldToDem(Scene& scene, bool tilesGiven);

// checkWorldScene's checks of a DEM world: vegetation.tile_size a whole number of DEM samples (at most
// kMaxHeightfieldCells), vegetation.world_origin on the DEM's lattice, and the tiles inside the DEM. Throws
// sward::Error naming the keys.
void checkDemWorld(const Scene& scene);

} // namespace sward
