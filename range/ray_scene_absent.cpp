// RayScene in a build without Embree (SWARD_WITH_EMBREE=OFF; range/CMakeLists.txt compiles this file instead of
// ray_scene.cpp and plant_fields.cpp): constructing one throws one error naming Embree and the option, so no scene
// with range sensors gets further (the scene parser refuses them first: scene/range_sensors.cpp).
#include "range/ray_scene.h"

#include "common/optional_components.h"

namespace sward {

struct RayScene::Impl {};

RayScene::RayScene(const Ground&, const Atlas&, const VegetationParams&, const VegetationTile*, uint32_t) {
    requireComponent(Component::Embree, "the range sensors' ray casting");
}

RayScene::RayScene(const Atlas&, const VegetationParams&, uint32_t, uint32_t) {
    requireComponent(Component::Embree, "the range sensors' ray casting");
}

RayScene::~RayScene() = default;

// Not reached: no RayScene is ever constructed in this build.
void RayScene::setPlants(const WindParams&, double, std::span<const gpu::PlantDynamic>, glm::dvec2, double, uint32_t) {}
void RayScene::setTiles(std::span<const RayTile>) {}
void RayScene::setObjects(const std::vector<PosedTriangles>&) {}
void RayScene::setGroundPatches(const std::vector<GroundPatch>&) {}
RangeHit RayScene::cast(glm::dvec3, glm::dvec3, double, double) const {
    return {};
}
void RayScene::cast8(glm::dvec3, std::span<const glm::dvec3>, double, double, RangeHit*) const {}
uint64_t RayScene::plantsPrepared() const {
    return 0;
}

} // namespace sward
