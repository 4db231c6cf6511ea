#include "heightfield.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sward;

TEST(Heightfield, ProceduralTerrainIsDeterministicAndSeeded) {
    ProceduralTerrainParams p{.size = 100.0f, .spacing = 2.0f, .seed = 7};
    Heightfield a = makeProceduralTerrain(p), b = makeProceduralTerrain(p);
    EXPECT_EQ(a.heights(), b.heights());
    p.seed = 8;
    EXPECT_NE(a.heights(), makeProceduralTerrain(p).heights());
    EXPECT_EQ(a.columns(), 51u);
    EXPECT_LT(a.minHeight(), a.maxHeight());
}

TEST(Heightfield, HeightInterpolatesTheRenderedTriangles) {
    // A single cell with one raised corner: heights follow the (0,0)-(1,1) diagonal split.
    Heightfield h(2, 2, 1.0f, glm::vec2(0.0f), {0.0f, 1.0f, 0.0f, 0.0f});
    EXPECT_FLOAT_EQ(h.height({1.0f, 0.0f}), 1.0f);
    EXPECT_FLOAT_EQ(h.height({0.75f, 0.25f}), 0.5f); // lower-right triangle (p00, p10, p11)
    EXPECT_FLOAT_EQ(h.height({0.25f, 0.75f}), 0.0f); // upper-left triangle (p00, p11, p01) is flat
    EXPECT_NEAR(glm::length(h.normal({0.75f, 0.25f})), 1.0f, 1e-6f);
}

TEST(Heightfield, RaycastHitsTheSurfaceExactly) {
    Heightfield h = makeProceduralTerrain({.size = 200.0f, .spacing = 2.0f, .amplitude = 20.0f, .seed = 3});
    glm::dvec3 origin(20.0, 30.0, 40.0);
    glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 0.8, -0.3));
    auto t = h.raycast(origin, dir, 1000.0);
    ASSERT_TRUE(t.has_value());
    glm::dvec3 p = origin + *t * dir;
    EXPECT_NEAR(p.z, h.height(glm::vec2(p)), 1e-4);
    EXPECT_FALSE(h.raycast(origin, glm::dvec3(0.0, 0.0, 1.0), 1000.0).has_value());
}
