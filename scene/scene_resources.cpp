#include "scene/scene_resources.h"

#include "common/error.h"
#include "scene/terrain.h"

namespace sward {

SceneResources buildSceneResources(Scene scene, bool withVegetation, uint32_t threads) {
    // One tile is what the renderers draw; a world of many is streamed (WorldTiles) but not drawn yet. Refusing it
    // beats a dataset of tile (0, 0) alone under a camera that flies away from it.
    if (scene.world.enabled && scene.world.tilesX * scene.world.tilesY > 1)
        throw Error(scene.source + ": 'world' (" + std::to_string(scene.world.tilesX) + " x " +
                    std::to_string(scene.world.tilesY) +
                    " tiles) is streamed by scene/world_tiles (sward-bench world) but not drawn yet: the renderers "
                    "and sward-view draw a one-tile scene");
    SceneResources r{.scene = std::move(scene)};
    r.terrain = buildTerrain(r.scene);
    r.models = loadObjectModels(r.scene.objects, r.scene.source);
    if (!withVegetation || !r.scene.vegetationEnabled) return r;
    const VegetationParams params = vegetationOn(r.scene, r.terrain);
    const GrassMap map = buildGrassMap(r.scene, params.tileSize);
    r.tile = buildVegetation(r.scene, r.terrain, map, threads);
    r.atlas = buildAtlas(r.scene);
    r.vegetation = true;
    require(r.atlas->desc.rows.size() >= r.scene.vegetation.categoryCount,
            r.scene.source + ": the atlas has " + std::to_string(r.atlas->desc.rows.size()) +
                " rows but 'vegetation' has " + std::to_string(r.scene.vegetation.categoryCount) +
                " categories (one row per category)");
    r.cover = makeCoverMap(map, *r.atlas, params);
    return r;
}

} // namespace sward
