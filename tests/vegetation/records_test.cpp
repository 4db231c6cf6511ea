#include "vegetation/records.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sward;

TEST(Records, OctahedralRoundTripIsAccurateOverTheSphere) {
    float worst = 0.0f;
    for (int i = 0; i < 64; ++i) {
        for (int j = 0; j < 32; ++j) {
            // A lattice of directions (spherical coordinates are fine here: tests need not be bitwise portable).
            const float phi = float(i) / 64.0f * 6.2831853f, theta = (float(j) + 0.5f) / 32.0f * 3.14159265f;
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            worst = std::max(worst, glm::length(decodeOctahedral(encodeOctahedral(n)) - n));
        }
    }
    EXPECT_LT(worst, 1e-4f); // < 0.006 degrees
}

TEST(Records, StaticRecordRoundTripsEveryField) {
    const PlantInstance p{.positionX = 65535,
                          .positionY = 12345,
                          .height = -3.25f,
                          .up = {0.0f, 0.6f, 0.8f},
                          .category = 3,
                          .variant = 63,
                          .orientation = 200,
                          .random = 17,
                          .size = 255};
    const PlantInstance q = decodePlantStatic(encodePlantStatic(p));
    EXPECT_EQ(q.positionX, p.positionX);
    EXPECT_EQ(q.positionY, p.positionY);
    EXPECT_EQ(q.height, p.height);
    EXPECT_LT(glm::length(q.up - p.up), 1e-4f);
    EXPECT_EQ(q.category, p.category);
    EXPECT_EQ(q.variant, p.variant);
    EXPECT_EQ(q.orientation, p.orientation);
    EXPECT_EQ(q.random, p.random);
    EXPECT_EQ(q.size, p.size);
}

TEST(Records, PositionDecodesFromFieldOriginAndStep) {
    const gpu::PlantStatic r = encodePlantStatic({.positionX = 65536 / 2, .positionY = 4, .height = 7.0f});
    const glm::vec3 p = decodePlantPosition(r, {475.0f, 25.0f}, 25.0f / 65536.0f);
    EXPECT_EQ(p, glm::vec3(487.5f, 25.0f + 4.0f * 25.0f / 65536.0f, 7.0f));
}

TEST(Records, DynamicRecordRoundTripsAndRestsUncut) {
    const PlantMotion m{
        .bend = {0.5f, -1.0f}, .bendVelocity = {2.0f, -4.0f}, .state = gpu::kPlantStateCut, .cutFraction = 0.4f};
    const PlantMotion d = decodePlantDynamic(encodePlantDynamic(m));
    EXPECT_NEAR(d.bend.x, 0.5f, 1e-4f);
    EXPECT_EQ(d.bend.y, -1.0f);
    EXPECT_NEAR(d.bendVelocity.x, 2.0f, gpu::kMaxBendVelocity / 511.0f);
    EXPECT_EQ(d.bendVelocity.y, -4.0f);
    EXPECT_EQ(d.state, gpu::kPlantStateCut);
    EXPECT_NEAR(d.cutFraction, 0.4f, 1.0f / 255.0f);

    const PlantMotion rest = decodePlantDynamic(restingPlantDynamic());
    EXPECT_EQ(rest.state, gpu::kPlantStateRest);
    EXPECT_EQ(rest.cutFraction, 1.0f);
    EXPECT_EQ(restingPlantDynamic().state >> 24, gpu::kPlantUncut);
}
