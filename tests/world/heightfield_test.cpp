#include "world/heightfield.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sward;
using namespace sward::test;

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

TEST(Heightfield, Loads16BitPngNorthUpWithVerticalScale) {
    const auto path = tempDir() / "height.png";
    writePng(path, 2, 2, 1, 16, {1.0f, 0.5f, 0.0f, 0.25f}); // top row = north = larger y
    const Heightfield h = loadHeightfield(path.string(), 100.0f, 4.0f, {10.0f, 20.0f}, -5.0f);
    EXPECT_EQ(h.extent(), glm::vec2(4.0f));
    EXPECT_FLOAT_EQ(h.height({10.0f, 24.0f}), 95.0f);
    EXPECT_NEAR(h.height({14.0f, 20.0f}), 20.0f, 1e-3f); // 0.25 is 16384 / 65535 in 16 bits
}

TEST(Heightfield, LoadsFloatExr) {
    const auto path = (tempDir() / "height.exr").string();
    writeExr(path, 2, 2, 1, {1.5f, 2.0f, -3.0f, 4.0f});
    const Heightfield h = loadHeightfield(path, 2.0f, 1.0f);
    EXPECT_EQ(h.sample(0, 0), -6.0f);
    EXPECT_EQ(h.sample(1, 1), 4.0f);
}

TEST(HeightfieldErrors, EightBitPngIsRejected) {
    const auto path = tempDir() / "height8.png";
    writePng(path, 2, 2, 1, 8, {0, 0, 0, 0});
    expectError([&] { loadHeightfield(path.string(), 1.0f, 1.0f); }, {path.string(), "8-bit"});
}

TEST(HeightfieldErrors, RgbImageHasTheWrongChannelCount) {
    const auto path = tempDir() / "heightrgb.png";
    writePng(path, 2, 2, 3, 16, std::vector<float>(12, 0.5f));
    expectError([&] { loadHeightfield(path.string(), 1.0f, 1.0f); }, {path.string(), "3 channels"});
}

TEST(HeightfieldErrors, NanHeightNamesFileAndPixel) {
    const auto path = (tempDir() / "nan.exr").string();
    writeExr(path, 2, 2, 1, {0, 0, 0, std::numeric_limits<float>::quiet_NaN()});
    expectError([&] { loadHeightfield(path, 1.0f, 1.0f); }, {path, "non-finite", "(1, 1)"});
}
