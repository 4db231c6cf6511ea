// Vehicles at a free pose (sward-view's keyboard rover) use exactly the collider construction of path-driven
// scene vehicles.
#include "world/heightfield.h"
#include "scene/vehicles.h"
#include "world/ground.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

sward::Ground hills() {
    sward::ProceduralTerrainParams p;
    p.size = 60.0f;
    p.spacing = 2.0f;
    p.amplitude = 6.0f;
    return sward::Ground(sward::makeProceduralTerrain(p));
}

} // namespace

TEST(VehiclePose, WheelsAtAPoseMatchThePathDrivenWheels) {
    sward::Ground terrain = hills();
    sward::VehicleParams v;
    v.path.points = {{10.0, 12.0}, {40.0, 31.0}};
    v.path.speed = 2.0;
    sward::PathPose pose = sward::pathPose(v.path, terrain, 3.0);
    auto fromPath = sward::vehicleWheels(v, terrain, 3.0);
    auto atPose = sward::vehicleWheelsAt(v, terrain, glm::dvec2(pose.position), pose.heading);
    ASSERT_EQ(fromPath.size(), 4u);
    ASSERT_EQ(atPose.size(), 4u);
    for (size_t w = 0; w < 4; ++w) {
        EXPECT_EQ(fromPath[w].centre, atPose[w].centre) << w;
        EXPECT_EQ(fromPath[w].axle, atPose[w].axle) << w;
    }
}

TEST(VehiclePose, WheelCollidersAreAxleCapsulesWithStableIds) {
    sward::Ground terrain = hills();
    sward::VehicleParams v;
    v.wheelWidth = 0.5f; // wider than the wheel's diameter: a capsule with a real segment
    auto wheels = sward::vehicleWheelsAt(v, terrain, {20.0, 20.0}, {0.0, 1.0});
    auto colliders = sward::wheelColliders(v, wheels, 2);
    ASSERT_EQ(colliders.size(), 4u);
    for (uint32_t w = 0; w < 4; ++w) {
        const sward::Collider& c = colliders[w];
        EXPECT_EQ(c.id, 3000u + w);
        EXPECT_EQ(c.shape, sward::ColliderShape::Capsule);
        EXPECT_FLOAT_EQ(c.radius, v.wheelRadius);
        EXPECT_FLOAT_EQ(c.force, v.weight);
        EXPECT_NEAR(glm::length(c.end - c.centre), v.wheelWidth - 2.0f * v.wheelRadius, 1e-5f);
        EXPECT_NEAR(glm::length(0.5f * (c.centre + c.end) - wheels[w].centre), 0.0f, 1e-5f);
        // Heading +y: the axle points along x (to the vehicle's left, -x).
        EXPECT_NEAR(std::abs(glm::normalize(c.end - c.centre).x), 1.0f, 1e-5f);
    }
    // The left wheels (0, 2) are on the -x side when heading +y.
    EXPECT_LT(wheels[0].centre.x, wheels[1].centre.x);
}
