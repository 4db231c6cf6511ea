#include "range/ray_scene.h"

#include "range_test_scene.h"
#include "vegetation/expansion_reference.h"
#include "vegetation/records.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sward {
namespace {

using test::uniformPatch;

// A ray aimed at a point of a plant's card where the atlas is opaque hits that card at exactly that point.
TEST(RayScene, HitsAPlantCardWhereItsAlphaIsOpaque) {
    const auto patch = uniformPatch(4.0);
    RayScene rays(patch.ground, patch.atlas, patch.scene.vegetation, &patch.tile);
    rays.setPlants(patch.scene.wind, 0.0, {}, {25.0, 25.0}, 100.0);
    const FieldVegetation& field = patch.tile.fields[0];
    ASSERT_GT(field.plantCount(), 10u);
    uint32_t checked = 0;
    for (uint32_t i = 0; i < field.plantCount() && checked < 20; i += 7) {
        const gpu::ExpandedPlant plant =
            expandWholePlant(patch.scene.vegetation, patch.scene.wind, field, i, field.dynamicRecords[i], 0.0);
        const AtlasDesc& desc = patch.atlas.desc;
        const uint32_t category = plant.attributes & 3u,
                       variant = ((plant.attributes >> 2) & 63u) % uint32_t(desc.rows[category].cells.size());
        const AtlasCell& cell = desc.rows[category].cells[variant];
        glm::vec3 corners[16];
        plantQuadCorners(plant, gpu::kLodNear, glm::vec3(0.0f), glm::vec3(cell.baseU, cell.baseV, cell.aspect),
                         corners);
        // The centre of quad 0's first triangle, approached along the quad's normal from 2 cm away.
        const glm::vec3 target = (corners[0] + corners[1] + corners[2]) / 3.0f;
        const glm::vec3 normal = glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
        const glm::dvec3 origin = glm::dvec3(target + 0.02f * normal);
        const RangeHit hit = rays.cast(origin, -glm::dvec3(normal), 0.0, 1.0);
        if (!hit.hit() || hit.distance > 0.0205f) continue; // transparent there: the ray went on
        EXPECT_NEAR(hit.distance, 0.02f, 2e-5f);
        EXPECT_EQ(hit.label & 0xffffffu, field.firstPlant + i + 1);
        EXPECT_EQ(hit.label >> gpu::kInstanceBits, gpu::kSemanticVegetation + 1u);
        EXPECT_NEAR(std::abs(glm::dot(hit.normal, normal)), 1.0f, 1e-5f);
        ++checked;
    }
    EXPECT_GE(checked, 5u);
}

// Straight down through bare ground's air: the ground at the heightfield's height, labelled ground, normal up.
TEST(RayScene, HitsTheGroundWhereNoPlantStands) {
    const auto patch = uniformPatch(0.0);
    RayScene rays(patch.ground, patch.atlas, patch.scene.vegetation, &patch.tile);
    rays.setPlants(patch.scene.wind, 0.0, {}, {25.0, 25.0}, 100.0);
    const RangeHit hit = rays.cast({12.3, 17.9, 3.0}, {0, 0, -1}, 0.0, 10.0);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.distance, 3.0f - patch.ground.height({12.3f, 17.9f}), 1e-5f);
    EXPECT_EQ(hit.label, gpu::kSemanticGround << gpu::kInstanceBits);
    EXPECT_NEAR(hit.normal.z, 1.0f, 1e-6f);
}

} // namespace
} // namespace sward
