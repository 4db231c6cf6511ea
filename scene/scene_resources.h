// SceneResources: everything a scene names, built on the CPU — the one assembly that sward-render, sward-view and
// sward-bench share. Building it checks every input (terrain, object models, vegetation budget, atlas), so bad
// input fails here, before a Vulkan object exists or a file is written.
#pragma once

#include "scene/objects.h"
#include "scene/scene.h"
#include "vegetation/atlas.h"
#include "vegetation/cover_map.h"
#include "vegetation/vegetation_tile.h"
#include "scene/world_tiles.h"
#include "world/ground.h"

#include <memory>

#include <optional>
#include <vector>

namespace sward {

struct SceneResources {
    Scene scene;
    Ground terrain;                     // one-tile scenes (a world's tiles have their own, in `world`)
    std::unique_ptr<WorldTiles> world;  // a world of several tiles: made resident around the cameras
    std::vector<ObjectModel> models;   // object k of scene.objects
    std::optional<VegetationTile> tile; // CPU copies, present when the vegetation is drawn; createSceneGpu
    std::optional<Atlas> atlas;         // releases them once uploaded, unless the simulation reads the tile
    std::optional<CoverMap> cover;      // the vegetation seen from beyond the far LOD limit (with the tile)
    bool vegetation = false;            // the vegetation is drawn (stays true after the copies are released)

    bool withVegetation() const { return vegetation; }
};

// Builds the scene's terrain, object models and, when `withVegetation` and the scene enables it, its vegetation
// tile (threads: 0 = all cores) and atlas. Checks that the atlas has a row per vegetation category. A "world" of
// several tiles gets its WorldTiles instead of a terrain and a tile (nothing generated yet; tiles carry their far
// cover when the vegetation is drawn).
SceneResources buildSceneResources(Scene scene, bool withVegetation = true, uint32_t threads = 0);

// The colliders acting during tick `tick`: sceneColliders on the scene's terrain, or in a world worldColliders.
std::vector<Collider> sceneColliders(const SceneResources& r, uint64_t tick);

} // namespace sward
