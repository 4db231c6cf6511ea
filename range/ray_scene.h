// RayScene: exactly what the cameras draw at one tick, for rays cast on the CPU with Embree (range sensors).
//
// - Ground: the drawn triangulation (a heightfield's cells split along the (i, j)-(i+1, j+1) diagonal, or the mesh's
//   triangles), one Embree triangle geometry built once (in a world: one per tile, built when the tile is first given).
// - Plants: every plant in the near LOD's four quads (vegetation/expansion_reference.h: the same records, wind, bend,
//   felled and cut states as the GPU expansion), whole quads, the atlas's level-0 alpha tested at 0.5 with bilinear
//   filtering at each hit, so rays pass through the gaps between blades. One Embree user geometry per 25 m field,
//   its boxes bounding the plant in any state (built once, when a field first comes within reach); per tick
//   setPlants() recomputes the quads of the fields within reach, and the intersector tests a plant's tight box, then
//   its eight triangles.
// - Objects: the scene objects' triangles posed at the tick (setObjects).
// - Ruts: the ground's rut patches at the tick, at their finest level (setGroundPatches), the coarse ground holed
//   under them as the renderer draws it; a hit where the rut is at least kTrackLabelDepth deep is labelled track.
//
// A world (scene.world, several tiles) gives its tiles with setTiles: the ground and plants of each, ascending (y, x),
// instanced in that order, so the scene (and every hit) depends only on which tiles are given, never on which others
// happen to be resident or in what order they were given before.
//
// Closest hits are unique: among hits at the same distance the lowest (geometry, primitive, triangle) key wins, so the
// result does not depend on traversal order. Embree builds on one thread (its BVHs do not depend on the machine), and
// rays are cast from any number of threads at once.
#pragma once

#include "vegetation/atlas.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"
#include "world/ground.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace sward {

struct RangeHit {
    float distance = 0.0f;  // along the ray's unit direction, metres; 0 = nothing hit
    uint32_t label = 0;     // (semantic class << kInstanceBits) | instance id, as the truth pass writes it
    glm::vec3 normal{0.0f}; // unit world normal of the surface hit, facing the ray's origin
    uint32_t tile = 0;      // a world's plant: its tile, y * tiles_x + x + 1 (the truth images' tile channel); else 0
    bool hit() const { return distance > 0.0f; }
};

// The triangles of one posed scene object, world space, with its truth label.
struct PosedTriangles {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices; // 3 per triangle
    uint32_t label = 0;
};

// A rut patch of the ground (render/track_renderer.h): ground-track block (blockX, blockY) drawn as a grid of
// gpu::kTrackPatchVertices^2 points (xyz, w the rut's depth), row by row, cells split along (i, j)-(i+1, j+1); the
// coarse ground has a hole over the block.
struct GroundPatch {
    int32_t blockX = 0, blockY = 0;
    std::vector<glm::vec4> points;
};

// One tile of a world as the range sensors see it (RayScene::setTiles).
struct RayTile {
    TileCoord coord;
    const Ground* ground = nullptr;
    const VegetationTile* plants = nullptr; // null: bare ground
};

class RayScene {
public:
    // `tile` (null: no plants) must outlive the scene; its dynamic records are read by setPlants. `nearBlades`:
    // lod.near_blades, the grass plants' blades instead of their quads (as the cameras draw them).
    RayScene(const Ground& ground, const Atlas& atlas, const VegetationParams& vegetation, const VegetationTile* tile,
             uint32_t nearBlades = 0);
    // A world's scene (`tilesX` tiles along x, for RangeHit::tile): no ground and no plants until setTiles gives them.
    RayScene(const Atlas& atlas, const VegetationParams& vegetation, uint32_t tilesX, uint32_t nearBlades = 0);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // A world's tiles for the next casts, ascending (y, x), replacing the previous ones: a tile given before (the same
    // coordinate, ground and plants) keeps its ground BVH and its fields. Each must stay valid until the next
    // setTiles; setPlants then reads every tile's own dynamic records. Requires the world constructor.
    void setTiles(std::span<const RayTile> tiles);

    // The plants at simulation time `time` (wind) in the interaction state `dynamics` (the tile's whole dynamic record
    // buffer, in tile order, as the GPU holds it; empty: the tile's own records; a world: empty, each tile's own): quads
    // of every field whose box lies within `reach` metres of `centre` (xy); plants of other fields are not hit. Threads as parallelFor.
    void setPlants(const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics, glm::dvec2 centre,
                   double reach, uint32_t threads = 0);
    // The scene objects' triangles at this tick (replaces the previous ones).
    void setObjects(const std::vector<PosedTriangles>& objects);
    // The ground's rut patches at this tick (replaces the previous ones; none: the ground as it was made).
    void setGroundPatches(const std::vector<GroundPatch>& patches);

    // The closest surface along origin + t * direction (direction unit) with t in [tNear, tFar].
    RangeHit cast(glm::dvec3 origin, glm::dvec3 direction, double tNear, double tFar) const;
    // The same for up to 8 rays from one origin, traversed together (a beam's sub-rays): hits[i] is what cast gives
    // for directions[i].
    void cast8(glm::dvec3 origin, std::span<const glm::dvec3> directions, double tNear, double tFar,
               RangeHit* hits) const;

    uint64_t plantsPrepared() const; // plants whose quads setPlants computed last

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace sward
