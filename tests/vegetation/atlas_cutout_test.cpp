// Cut-out polygons of atlas cells (vegetation/atlas_cutout.cpp): conservative for every texel the alpha test can keep.
#include "vegetation/atlas_cutout.h"

#include "atlas_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace sward;
using namespace sward::test;

namespace {

// Counts the texels of levels 0..kCutoutMaxLevel with alpha >= minAlpha whose footprint, grown by the bilinear
// filter's reach (one texel of the level), lies in the cell's polygon; `outside` counts those that do not.
void countTexels(const Atlas& atlas, const std::vector<CutoutPolygon>& polygons, uint8_t minAlpha, size_t& inside,
                 size_t& outside) {
    const uint32_t columns = atlas.desc.maxColumns();
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c)
            for (uint32_t level = 0; level <= gpu::kCutoutMaxLevel; ++level) {
                const AtlasMip& mip = atlas.mips[level];
                const AtlasRect rect = atlas.desc.cellRect(r, c, level);
                const float tu = 1.0f / float(rect.width), tv = 1.0f / float(rect.height);
                for (uint32_t y = 0; y < rect.height; ++y)
                    for (uint32_t x = 0; x < rect.width; ++x) {
                        if (mip.rgba[(size_t(rect.y + y) * mip.width + rect.x + x) * 4 + 3] < minAlpha) continue;
                        bool in = true;
                        for (float dy : {-1.0f, 2.0f})
                            for (float dx : {-1.0f, 2.0f}) {
                                glm::vec2 p(std::clamp((float(x) + dx) * tu, 0.0f, 1.0f),
                                            std::clamp((float(y) + dy) * tv, 0.0f, 1.0f));
                                in = in && polygons[r * columns + c].contains(p);
                            }
                        (in ? inside : outside) += 1;
                    }
            }
}

} // namespace

TEST(AtlasCutout, PolygonHoldsEveryTexelTheAlphaTestCanKeep) {
    const Atlas& atlas = defaultAtlasWithMips(true);
    for (uint32_t corners = 4; corners <= gpu::kMaxCutoutCorners; ++corners) {
        const std::vector<CutoutPolygon> polygons = atlasCutouts(atlas, corners);
        size_t passing = 0, passingOutside = 0, visible = 0, visibleOutside = 0;
        countTexels(atlas, polygons, 128, passing, passingOutside); // alpha >= 0.5: the alpha test at 1x
        countTexels(atlas, polygons, 1, visible, visibleOutside);   // alpha > 0: alpha-to-coverage may keep these
        std::printf("%u corners: texels (levels 0..%u) passing 0.5: %zu, with alpha > 0: %zu, outside: %zu\n", corners,
                    gpu::kCutoutMaxLevel, passing, visible, visibleOutside);
        EXPECT_EQ(passingOutside, 0u) << corners << " corners";
        EXPECT_EQ(visibleOutside, 0u) << corners << " corners";
        EXPECT_GT(passing, 100000u); // the test saw the atlas's plants, not an empty image
    }
}

TEST(AtlasCutout, PolygonsAreConvexWithinTheCellWithAtMostTheCornersAskedFor) {
    const Atlas& atlas = defaultAtlasWithMips(true);
    for (uint32_t corners = 4; corners <= gpu::kMaxCutoutCorners; ++corners) {
        const std::vector<CutoutPolygon> polygons = atlasCutouts(atlas, corners);
        const uint32_t columns = atlas.desc.maxColumns();
        double area = 0.0;
        uint32_t cells = 0;
        for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
            for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) {
                const CutoutPolygon& p = polygons[r * columns + c];
                ASSERT_GE(p.count, 3u);
                ASSERT_LE(p.count, corners);
                for (uint32_t i = 0; i < p.count; ++i) {
                    const glm::vec2 a = p.corners[i], b = p.corners[(i + 1) % p.count],
                                    n = p.corners[(i + 2) % p.count];
                    EXPECT_GE((b - a).x * (n - b).y - (b - a).y * (n - b).x, -1e-6f) << "cell " << r << "," << c;
                    EXPECT_TRUE(a.x >= 0.0f && a.x <= 1.0f && a.y >= 0.0f && a.y <= 1.0f);
                }
                for (uint32_t i = p.count; i < gpu::kMaxCutoutCorners; ++i)
                    EXPECT_EQ(p.corners[i], p.corners[p.count - 1]);
                area += p.area();
                ++cells;
            }
        std::printf("%u corners: mean cut-out area %.3f of the cell over %u cells\n", corners, area / cells, cells);
        // The built-in plants fill most of their cells, and the margin grown at level kCutoutMaxLevel (16 x 16 texels a
    // cell) is 2 / 16 of a cell on each side: about 0.81 (8 corners) to 0.88 (4 corners) of a cell remains.
    EXPECT_LT(area / cells, 0.9);
    }
}

TEST(AtlasCutout, AnEmptyCellKeepsTheWholeQuad) {
    Atlas atlas = generateAtlas(smallParams());
    std::fill(atlas.mips[0].rgba.begin(), atlas.mips[0].rgba.end(), uint8_t(0));
    buildMipChain(atlas);
    const std::vector<CutoutPolygon> polygons = atlasCutouts(atlas);
    ASSERT_FALSE(polygons.empty());
    for (const CutoutPolygon& p : polygons) EXPECT_FLOAT_EQ(p.area(), 1.0f);
}
