// The horizon ring (issue 51, part 3): a world draws its tiles' ground out to world.view_distance; beyond it, the
// terrain goes on as a coarse heightfield of the whole world (scene/world_horizon.h), shaded with the vegetation's
// far cover and labelled ground, so no sky shows below the horizon. It is drawn by the terrain's own pipelines in the
// main and truth passes (not in the shadow pass: it lies beyond the shadow cascades), after the tiles; the tiles'
// ground keeps to the disc of view_distance around the reference camera and the ring to the world outside it
// (shaders/shared/horizon_ring.glsl), both decided per fragment from the camera alone, so a frame never depends on
// which tiles happen to be resident. SceneRenderer's world constructor makes it (world.horizon, on by default).
#pragma once

#include "render/ground_mesh.h"
#include "vegetation/cover_map.h"
#include "world/heightfield.h"

#include <span>

namespace sward {

struct Scene;

// The ring's draw mesh: the heightfield's grid as groundDrawMesh draws it, each vertex marked as the ring's by its
// rim width in normal.w (the cell's diagonal, widened 1 %) and its floor `floorHeight` in uvLayer.w (the lowest
// height the world's ground can have): horizon_ring.glsl sinks the vertices within the rim width of the disc to the
// floor, so every ring triangle the disc's edge crosses lies below the tiles' ground there.
GroundDrawMesh horizonRingMesh(const Heightfield& heights, float floorHeight);

// The ring's far cover: the scene's procedural meadow (makeMeadowGrassMap), or a world's land cover point-sampled
// (worldLandCoverPointMap), over the square of the ring's longer side,
// one grass-map texel per ring cell (at most kMaxCoverMapEdge a side), seen from afar through the categories' looks
// (makeCoverMap). Point samples of the meadow: the ring shows its large patches, not its few-metre clusters.
CoverMap horizonCover(const Scene& scene, const Heightfield& heights, std::span<const CategoryLook> looks);

} // namespace sward
