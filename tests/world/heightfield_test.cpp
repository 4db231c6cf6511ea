#include "world/heightfield.h"
#include "io/image_files.h"
#include "io/image_io.h"
#include "common/error.h"
#include "common/noise.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <bit>
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

TEST(Heightfield, NeighbouringProceduralTilesShareTheirEdgeBitwise) {
    const ProceduralTerrainParams base{.size = 100.0f, .spacing = 2.0f, .amplitude = 20.0f, .seed = 9};
    ProceduralTerrainParams east = base, north = base;
    east.origin = {100.0, 0.0};
    north.origin = {0.0, 100.0};
    const Heightfield a = makeProceduralTerrain(base), b = makeProceduralTerrain(east), c = makeProceduralTerrain(north);
    ASSERT_EQ(a.columns(), 51u);
    EXPECT_EQ(b.origin(), glm::vec2(100.0f, 0.0f));
    for (uint32_t k = 0; k < a.columns(); ++k) {
        EXPECT_EQ(std::bit_cast<uint32_t>(a.sample(a.columns() - 1, k)), std::bit_cast<uint32_t>(b.sample(0, k)));
        EXPECT_EQ(std::bit_cast<uint32_t>(a.sample(k, a.rows() - 1)), std::bit_cast<uint32_t>(c.sample(k, 0)));
    }
}

TEST(Heightfield, AProceduralTileIsAWindowOnTheWorldTerrain) {
    const ProceduralTerrainParams world{.size = 200.0f, .spacing = 2.0f, .amplitude = 20.0f, .seed = 4};
    ProceduralTerrainParams tile = world;
    tile.size = 100.0f;
    tile.origin = {100.0, 60.0};
    const Heightfield w = makeProceduralTerrain(world), t = makeProceduralTerrain(tile);
    for (uint32_t j = 0; j < t.rows(); ++j)
        for (uint32_t i = 0; i < t.columns(); ++i)
            ASSERT_EQ(std::bit_cast<uint32_t>(t.sample(i, j)), std::bit_cast<uint32_t>(w.sample(i + 50, j + 30)));
}

TEST(Heightfield, ProceduralTerrainAtOriginZeroIsTheSingleTileTerrain) {
    // The single-tile terrain evaluates vertex (i, j) at x = i * spacing, y = j * spacing: a world's origin must
    // not change one bit of it.
    const ProceduralTerrainParams p{.size = 40.0f, .spacing = 0.5f, .amplitude = 7.0f, .featureSize = 30.0f,
                                    .octaves = 3, .seed = 11};
    const Heightfield h = makeProceduralTerrain(p);
    for (uint32_t j = 0; j < h.rows(); j += 7)
        for (uint32_t i = 0; i < h.columns(); i += 5) {
            const double x = double(i) * p.spacing, y = double(j) * p.spacing;
            double sum = 0.0, weight = 1.0, frequency = 1.0 / p.featureSize, norm = 0.0;
            for (uint32_t o = 0; o < p.octaves; ++o) {
                sum += weight * valueNoise(p.seed, o, x * frequency, y * frequency);
                norm += weight;
                weight *= 0.45;
                frequency *= 2.0;
            }
            ASSERT_EQ(std::bit_cast<uint32_t>(h.sample(i, j)), std::bit_cast<uint32_t>(float(0.5 * p.amplitude * sum / norm)));
        }
}

TEST(Heightfield, ProceduralOriginOffTheLatticeIsRefused) {
    ProceduralTerrainParams p{.size = 100.0f, .spacing = 2.0f};
    p.origin = {101.0, 0.0};
    EXPECT_THROW(makeProceduralTerrain(p), Error);
}

// An 8192^2 GeoTIFF of 0.3 MB took 6.2 GB and then VK_ERROR_OUT_OF_DEVICE_MEMORY: the ground is priced once the
// heightmap's size is known, before its heights are copied or meshed.
TEST(HeightfieldErrors, AHeightmapOverTheSampleLimitIsRefusedNamingItsCost) {
    const std::string path = (tempDir() / "big.png").string();
    const uint32_t width = 4098, height = 4097; // 4097^2 + 4097 samples
    writePng16(path, width, height, 1, std::vector<uint16_t>(size_t(width) * height, 0));
    expectError([&] { loadHeightfield(path, 1.0f, 1.0f); },
                {path, "4098x4097 = 16789506 samples: its ground would take about 1537 MiB, over the limit of "
                       "16785409 samples (4097x4097)"});
}
