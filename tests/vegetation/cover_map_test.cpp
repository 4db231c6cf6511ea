// The cover map: the far band's colour and hidden area per grass-map texel, and at most kMaxCoverMapEdge texels per
// edge (a 16384^2 grass map's cover took 4 GiB on the host and as much again on the GPU).
#include "vegetation/cover_map.h"

#include <gtest/gtest.h>

#include <vector>

using namespace sward;

namespace {

std::vector<CategoryLook> looks(const VegetationParams& params) {
    std::vector<CategoryLook> out(params.categoryCount);
    for (size_t c = 0; c < out.size(); ++c)
        out[c] = {glm::vec3(0.1f * float(c + 1), 0.5f, 0.2f), 0.3 + 0.1 * double(c)};
    return out;
}

} // namespace

TEST(CoverMap, ASmallMapIsCoveredTexelForTexel) {
    const VegetationParams params;
    const GrassMap map(3, 2, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.5f, 0, 0.2f, 0.3f, 0.4f}, "m");
    const CoverMap cover = makeCoverMap(map, looks(params), params);
    ASSERT_EQ(cover.width, 3u);
    ASSERT_EQ(cover.height, 2u);
    EXPECT_EQ(cover.texels[0], glm::vec4(0.0f)) << "no plants: no cover";
    const double area = 1.0 * params.categories[0].density * params.densityMultiplier * 0.3;
    EXPECT_EQ(cover.texels[1], glm::vec4(glm::vec3(looks(params)[0].colour), float(area)));
}

TEST(CoverMap, AMapOverTheEdgeLimitIsAveragedInBlocks) {
    const VegetationParams params;
    const uint32_t width = 2 * kMaxCoverMapEdge + 1, height = 4; // f = 3: 1366 x 2 texels
    std::vector<float> values(size_t(width) * height * 3, 0.0f);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) values[(size_t(y) * width + x) * 3 + 1] = float(x % 3) * 0.25f; // G
    const CoverMap cover = makeCoverMap(GrassMap(width, height, 3, values, "big"), looks(params), params);
    ASSERT_EQ(cover.width, 1366u);
    ASSERT_EQ(cover.height, 2u);
    // Each full block holds G = 0, 0.25, 0.5 in every row: its mean, 0.25, covers as a one-texel map of 0.25 does.
    const CoverMap one = makeCoverMap(GrassMap(1, 1, 3, {0.0f, 0.25f, 0.0f}, "one"), looks(params), params);
    EXPECT_EQ(cover.texels[0], one.texels[0]);
    EXPECT_EQ(cover.texels[size_t(1) * cover.width + 1364], one.texels[0]);
    // The last column's block is clipped to the map's last two texel columns (x = 4095, 4096: G = 0, 0.25).
    const CoverMap eighth = makeCoverMap(GrassMap(1, 1, 3, {0.0f, 0.125f, 0.0f}, "one"), looks(params), params);
    EXPECT_EQ(cover.texels[1365], eighth.texels[0]);
}

TEST(CoverMap, GroundMaterialWeightsAreTheCategoriesGrassMapValuesOnlyWhenACategoryHasAMaterial) {
    VegetationParams params;
    const GrassMap map(2, 1, 3, {0.25f, 0.5f, 0.0f, 0.0f, 0.0f, 1.0f}, "m");
    EXPECT_TRUE(makeCoverMap(map, looks(params), params).groundWeights.empty()) << "no material: nothing to blend";
    params.categories[1].groundMaterial = 2;            // mud
    params.channelCategory = {0, 1, 1, kUnusedChannel}; // G and B both feed category 1
    const CoverMap cover = makeCoverMap(map, looks(params), params);
    ASSERT_EQ(cover.groundWeights.size(), cover.texels.size());
    EXPECT_EQ(cover.groundWeights[0], glm::vec4(0.25f, 0.5f, 0.0f, 0.0f));
    EXPECT_EQ(cover.groundWeights[1], glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
}

TEST(CoverMap, GroundMaterialWeightsAreAveragedInTheTexelsBlocks) {
    VegetationParams params;
    params.categories[2].groundMaterial = 1;                     // dry soil
    const uint32_t width = 2 * kMaxCoverMapEdge + 1, height = 4; // f = 3: 1366 x 2 texels
    std::vector<float> values(size_t(width) * height * 3, 0.0f);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            values[(size_t(y) * width + x) * 3 + 1] = float(x % 3) * 0.25f;      // G
            values[(size_t(y) * width + x) * 3 + 2] = x % 3 == 0 ? 0.75f : 0.0f; // B
        }
    const CoverMap cover = makeCoverMap(GrassMap(width, height, 3, values, "big"), looks(params), params);
    ASSERT_EQ(cover.groundWeights.size(), size_t(1366) * 2);
    EXPECT_EQ(cover.groundWeights[0], glm::vec4(0.0f, 0.25f, 0.25f, 0.0f));
    EXPECT_EQ(cover.groundWeights[size_t(1) * cover.width + 1364], glm::vec4(0.0f, 0.25f, 0.25f, 0.0f));
    // The last column's block is clipped to x = 4095, 4096: G = 0, 0.25; B = 0.75, 0.
    EXPECT_EQ(cover.groundWeights[1365], glm::vec4(0.0f, 0.125f, 0.375f, 0.0f));
}
