#include "scene/world_objects.h"

#include "common/error.h"
#include "scene/scene.h"
#include "scene/world_tiles.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

// Distance from xy to the square of tile `coord`.
double distanceToTile(const Scene& scene, TileCoord coord, glm::dvec2 xy) {
    const double s = scene.vegetation.tileSize;
    const glm::dvec2 lo = glm::dvec2(scene.vegetation.worldOrigin) + s * glm::dvec2(coord.x, coord.y), hi = lo + s;
    const glm::dvec2 d = glm::max(glm::dvec2(0.0), glm::max(lo - xy, xy - hi));
    return std::sqrt(d.x * d.x + d.y * d.y);
}

} // namespace

Ground objectGround(const Scene& scene, const ObjectParams& object, const ObjectModel& model, double time) {
    require(scene.world.enabled, "objectGround: the scene has no 'world'");
    // objectPose reads the heights under the corners of the footprint, a box around the turned model's xy bounds:
    // within sqrt(2) times the model's farthest corner.
    double reach = 0.0;
    for (const glm::vec3& corner :
         {model.boundsMin, model.boundsMax, glm::vec3(model.boundsMin.x, model.boundsMax.y, 0),
          glm::vec3(model.boundsMax.x, model.boundsMin.y, 0)})
        reach = std::max(reach, glm::length(glm::dvec2(corner)));
    const glm::dvec2 centre = pathPoseXY(object.path, time);
    return latticeGround(scene, centre, centre, std::sqrt(2.0) * reach * object.scale);
}

RigCameras worldRig(const Scene& scene, const std::vector<ObjectModel>& models, uint32_t width, uint32_t height,
                    double time) {
    const RigParams& rig = scene.camera.rig;
    for (size_t k = 0; k < scene.objects.size() && k < models.size(); ++k)
        if (rig.mounted() && scene.objects[k].name == rig.mountObject)
            return sceneRig(scene, objectGround(scene, scene.objects[k], models[k], time), models, width, height, time);
    return sceneRig(scene, cameraGround(scene, time), models, width, height, time);
}

std::vector<Collider> worldGusts(const Scene& scene, uint64_t tick, glm::dvec2 camera) {
    const GustParams& params = scene.actors.gusts;
    if (params.count == 0) return {};
    const WorldParams& w = scene.world;
    const glm::vec2 lo = scene.vegetation.worldOrigin;
    const glm::vec2 hi = lo + scene.vegetation.tileSize * glm::vec2(float(w.tilesX), float(w.tilesY));
    // Heights above the ground under each centre, added below: the world's lowest and highest points are unknown
    // without generating every tile.
    const Aabb area{glm::vec3(lo, 0.0f), glm::vec3(hi, params.height)};
    std::vector<Collider> gusts;
    for (Collider gust : makeGusts(params.seed, params.count, area, tick, float(scene.sequence.timeStep))) {
        const std::vector<TileCoord> reached = tilesReached(scene, gust);
        if (!std::all_of(reached.begin(), reached.end(),
                         [&](TileCoord t) { return distanceToTile(scene, t, camera) <= w.viewDistance; }))
            continue;
        const glm::dvec2 xy(gust.centre);
        const float ground = latticeGround(scene, xy, xy, 0.0).height(glm::vec2(gust.centre));
        gust.centre.z += ground;
        gust.end.z += ground;
        gusts.push_back(gust);
    }
    return gusts;
}

std::vector<Collider> worldColliders(const Scene& scene, const std::vector<ObjectModel>& models, uint64_t tick) {
    require(models.size() == scene.objects.size(), "worldColliders: one model per scene object is required");
    const double time = double(tick) * scene.sequence.timeStep;
    std::vector<Collider> colliders = worldActorColliders(scene, time);
    if (scene.actors.gusts.count > 0) {
        const glm::dvec2 camera(worldRig(scene, models, 16, 16, time).left.position);
        const std::vector<Collider> gusts = worldGusts(scene, tick, camera);
        colliders.insert(colliders.end(), gusts.begin(), gusts.end());
    }
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        if (scene.objects[k].colliders.empty()) continue;
        const ObjectParams& object = scene.objects[k];
        const std::vector<Collider> own =
            objectColliders(object, models[k], k, objectGround(scene, object, models[k], time), time);
        colliders.insert(colliders.end(), own.begin(), own.end());
    }
    return colliders;
}

} // namespace sward
