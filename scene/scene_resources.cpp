#include "scene/scene_resources.h"

#include "common/error.h"
#include "scene/terrain.h"
#include "scene/world_objects.h"

namespace sward {

namespace {

void checkAtlasRows(const SceneResources& r) {
    require(r.atlas->desc.rows.size() >= r.scene.vegetation.categoryCount,
            r.scene.source + ": the atlas has " + std::to_string(r.atlas->desc.rows.size()) +
                " rows but 'vegetation' has " + std::to_string(r.scene.vegetation.categoryCount) +
                " categories (one row per category)");
}

} // namespace

SceneResources buildSceneResources(Scene scene, bool withVegetation, uint32_t threads) {
    SceneResources r{.scene = std::move(scene)};
    if (r.scene.world.enabled && r.scene.world.tilesX * r.scene.world.tilesY > 1) {
        checkWorldDrawable(r.scene);
        std::vector<CategoryLook> looks;
        if (withVegetation && r.scene.vegetationEnabled) {
            r.atlas = buildAtlas(r.scene);
            checkAtlasRows(r);
            looks = categoryLooks(*r.atlas, r.scene.vegetation);
            r.vegetation = true;
        } else {
            r.scene.vegetationEnabled = false; // tiles of bare ground: nothing to generate
        }
        r.world = std::make_unique<WorldTiles>(r.scene, threads, std::move(looks));
        r.models = loadObjectModels(r.scene.objects, r.scene.source);
        return r;
    }
    r.terrain = buildTerrain(r.scene);
    r.models = loadObjectModels(r.scene.objects, r.scene.source);
    if (!withVegetation || !r.scene.vegetationEnabled) return r;
    const VegetationParams params = vegetationOn(r.scene, r.terrain);
    const GrassMap map = buildGrassMap(r.scene, params.tileSize);
    r.tile = buildVegetation(r.scene, r.terrain, map, threads);
    r.atlas = buildAtlas(r.scene);
    r.vegetation = true;
    checkAtlasRows(r);
    r.cover = makeCoverMap(map, *r.atlas, params);
    return r;
}

std::vector<Collider> sceneColliders(const SceneResources& r, uint64_t tick) {
    if (r.world) return worldColliders(r.scene, r.models, tick);
    return sceneColliders(r.scene, r.models, r.terrain, tick);
}

} // namespace sward
