#include "vegetation/grass_map.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sward;
using namespace sward::test;

namespace {
// 2x2 RGB map, top row first: NW red, NE green, SW blue, SE white.
const std::vector<float> kCorners = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
} // namespace

TEST(GrassMap, Loads8BitPng) {
    const auto path = tempDir() / "map.png";
    writePng(path, 2, 2, 3, 8, kCorners);
    const GrassMap map = loadGrassMap(path.string());
    EXPECT_EQ(map.channels(), 3u);
    EXPECT_EQ(map.sample({0.0f, 1.0f}), glm::vec4(1, 0, 0, 0)); // north-west corner
    EXPECT_EQ(map.sample({1.0f, 0.0f}), glm::vec4(1, 1, 1, 0)); // south-east corner
}

TEST(GrassMap, Loads16BitPngAtFullPrecision) {
    const auto path = tempDir() / "map16.png";
    writePng(path, 1, 1, 4, 16, {1000.0f / 65535.0f, 0.5f, 0.0f, 1.0f});
    const GrassMap map = loadGrassMap(path.string());
    EXPECT_EQ(map.channels(), 4u);
    EXPECT_FLOAT_EQ(map.sample({0.5f, 0.5f}).x, 1000.0f / 65535.0f); // not representable in 8 bits
}

TEST(GrassMap, LoadsFloatExr) {
    const auto path = (tempDir() / "map.exr").string();
    writeExr(path, 2, 2, 3, {0.5f, 2.0f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3.0f});
    const GrassMap map = loadGrassMap(path);
    EXPECT_EQ(map.sample({0.0f, 1.0f}), glm::vec4(0.5f, 2.0f, 0.0f, 0.0f)); // floats above 1 are kept
    EXPECT_EQ(map.sample({1.0f, 0.0f}).z, 3.0f);
}

TEST(GrassMap, SamplesBilinearlyBetweenPixelCentres) {
    const GrassMap map(2, 2, 3, kCorners, "corners");
    EXPECT_FLOAT_EQ(map.sample({0.5f, 0.5f}).x, 0.5f);  // centre: mean of NW (1) and SE (1) and zeros
    EXPECT_FLOAT_EQ(map.sample({0.5f, 0.75f}).x, 0.5f); // north row centre line: halfway red..0
    EXPECT_FLOAT_EQ(map.sample({0.375f, 0.75f}).x, 0.75f);
}

TEST(GrassMap, MeanIntensityIsTheBilinearIntegral) {
    const GrassMap map(2, 2, 3, kCorners, "corners");
    double sum = 0.0;
    const int n = 400;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) sum += map.sample({(i + 0.5f) / n, (j + 0.5f) / n}).x;
    EXPECT_NEAR(map.meanIntensity(0), sum / (n * n), 1e-4);
}

TEST(GrassMap, MeadowIsMostlyGrassWithFernsAndFlowers) {
    const GrassMap a = makeMeadowGrassMap({.resolution = 128, .seed = 3});
    EXPECT_EQ(a.values(), makeMeadowGrassMap({.resolution = 128, .seed = 3}).values());
    EXPECT_NE(a.values(), makeMeadowGrassMap({.resolution = 128, .seed = 4}).values());
    EXPECT_GT(a.meanIntensity(1), 0.5);
    EXPECT_GT(a.meanIntensity(0), 0.02);
    EXPECT_GT(a.meanIntensity(2), 0.02);
    EXPECT_GT(a.meanIntensity(1), a.meanIntensity(0) + a.meanIntensity(2));
}

TEST(GrassMapErrors, MissingFileNamesTheFile) {
    const auto path = (tempDir() / "absent.png").string();
    expectError([&] { loadGrassMap(path); }, {path, "missing"});
}

TEST(GrassMapErrors, UnsupportedFormatNamesTheExtension) {
    const auto path = tempDir() / "map.bmp";
    std::ofstream(path) << "BM";
    expectError([&] { loadGrassMap(path.string()); }, {path.string(), "unsupported format", ".bmp"});
}

TEST(GrassMapErrors, FourBitPngIsAnUnsupportedBitDepth) {
    const auto path = tempDir() / "map4.png";
    writePngRaw(path, 2, 1, 4, 0, {0x3f});
    expectError([&] { loadGrassMap(path.string()); }, {path.string(), "unsupported bit depth 4"});
}

TEST(GrassMapErrors, CorruptPngNamesTheFile) {
    const auto path = tempDir() / "corrupt.png";
    std::ofstream(path) << "not a png at all, just some text";
    expectError([&] { loadGrassMap(path.string()); }, {path.string(), "not a valid PNG"});
}

TEST(GrassMapErrors, GreyImageHasTheWrongChannelCount) {
    const auto path = tempDir() / "grey.png";
    writePng(path, 2, 2, 1, 8, {0, 0.5f, 1, 0});
    expectError([&] { loadGrassMap(path.string()); }, {path.string(), "1 channel", "RGB"});
}

TEST(GrassMapErrors, NanDensityNamesFileAndPixel) {
    const auto path = (tempDir() / "nan.exr").string();
    writeExr(path, 2, 1, 3, {0, 0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0});
    expectError([&] { loadGrassMap(path); }, {path, "NaN", "channel G", "pixel (1, 0)"});
}

TEST(GrassMapErrors, NegativeDensityNamesFileAndValue) {
    const auto path = (tempDir() / "negative.exr").string();
    writeExr(path, 1, 1, 3, {0, 0, -0.25f});
    expectError([&] { loadGrassMap(path); }, {path, "-0.25", "channel B", ">= 0"});
}
