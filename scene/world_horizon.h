// A world's horizon (issue 51, part 3): beyond world.view_distance, where no tile is drawn, the ground goes on as a
// coarse heightfield of the whole world, so no sky shows below the horizon (render/horizon_ring.h draws it).
#pragma once

#include "world/heightfield.h"

namespace sward {

struct Scene;

// The world's terrain on the horizon ring's lattice (horizonSpacing, k times terrain.spacing) over the whole world,
// from vegetation.world_origin to the first lattice line at or beyond its north-east corner: sample (i, j) is bitwise
// the tiles' height at the fine lattice's vertex (k i, k j) from the world's origin (the same function at the same
// lattice index), so the ring meets the tiles' ground at its vertices. A DEM world's ring is one stepped window of the
// DEM (readRasterWindow: every k-th sample exactly), ending at the last ring line inside the DEM; a nodata sample
// there is an error naming the file and the pixel, as a tile's would be. Requires a world of the procedural terrain or
// a DEM.
Heightfield horizonHeights(const Scene& scene);

} // namespace sward
