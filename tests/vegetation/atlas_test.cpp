// The atlas's structure (vegetation/atlas.cpp): the cell grid, colour bleeding and the coverage-preserving mips.
#include "vegetation/atlas.h"

#include "atlas_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace sward;
using namespace sward::test;

TEST(Atlas, CellRectsAndUvsTileTheImage) {
    const AtlasDesc& desc = defaultAtlas().desc;
    const AtlasRect r = desc.cellRect(2, 5, 3);
    EXPECT_EQ(r.x, 5u * 32u);
    EXPECT_EQ(r.y, 2u * 32u);
    EXPECT_EQ(r.width, 32u);
    const auto uv = desc.cellUvRect(1, 2);
    EXPECT_FLOAT_EQ(uv[0], 2.0f / 12.0f); // 12 columns: the grass row
    EXPECT_FLOAT_EQ(uv[1], 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(uv[2], 3.0f / 12.0f);
    EXPECT_FLOAT_EQ(uv[3], 2.0f / 3.0f);
}

TEST(Atlas, TransparentTexelsCarryNearbyColour) {
    // Without colour bleeding, transparent texels would be black and filtering would darken every silhouette.
    const Atlas& atlas = defaultAtlas();
    const AtlasMip& image = atlas.mips[0];
    size_t transparent = 0, black = 0;
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) {
            const AtlasRect rect = atlas.desc.cellRect(r, c);
            for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
                for (uint32_t x = rect.x; x < rect.x + rect.width; ++x) {
                    const uint8_t* t = &image.rgba[(size_t(y) * image.width + x) * 4];
                    if (t[3] != 0) continue;
                    ++transparent;
                    black += t[0] < 8 && t[1] < 8 && t[2] < 8;
                }
        }
    EXPECT_GT(transparent, 0u);
    EXPECT_EQ(black, 0u);
}

TEST(Atlas, MipsKeepAlphaCoverage) {
    const Atlas& atlas = defaultAtlasWithMips(true);
    ASSERT_EQ(atlas.mips.size(), 9u);
    EXPECT_EQ(atlas.mips[8].width, 12u);
    EXPECT_EQ(atlas.mips[8].height, 3u);
    // Down to 8x8 texel cells (level 5): below that one texel is more than 1.5% of the cell and coverage can
    // only be matched in coarse steps.
    for (uint32_t l = 1; l <= 5; ++l)
        for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
            for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) {
                const float base = alphaCoverage(atlas.mips[0], atlas.desc.cellRect(r, c, 0), 0.5f);
                const float level = alphaCoverage(atlas.mips[l], atlas.desc.cellRect(r, c, l), 0.5f);
                EXPECT_NEAR(level, base, 0.05f) << "level " << l << " row " << r << " column " << c;
            }
}

TEST(Atlas, PlainBoxFilteredMipsLoseCoverage) {
    // The reason for coverage preservation: averaging thin blades with the gaps between them pushes alpha below
    // the reference, and distant grass would thin out. Somewhere between 16x16 and 4x4 texel cells (levels 4-6)
    // plain box filtering loses over a tenth of the grass row's coverage (the default atlas: 0.89, 0.92, 0.81 of
    // level 0); MipsKeepAlphaCoverage shows the preserved chain does not.
    const Atlas& atlas = defaultAtlasWithMips(false);
    const uint32_t columns = uint32_t(atlas.desc.rows[1].cells.size());
    float base = 0.0f, worst = 1e30f;
    for (uint32_t c = 0; c < columns; ++c) base += alphaCoverage(atlas.mips[0], atlas.desc.cellRect(1, c, 0), 0.5f);
    for (uint32_t l = 4; l <= 6; ++l) {
        float level = 0.0f;
        for (uint32_t c = 0; c < columns; ++c)
            level += alphaCoverage(atlas.mips[l], atlas.desc.cellRect(1, c, l), 0.5f);
        worst = std::min(worst, level);
    }
    EXPECT_LT(worst, 0.9f * base);
}

TEST(Atlas, ShadowLevelIsTheCoarsestWithTexelsNoLargerThanTheMaps) {
    // 256-texel cells on a 0.5 m plant: a level-l texel is 0.5 * 2^l / 256 m.
    auto texel = [](uint32_t l) { return 0.5 * double(1u << l) / 256.0; };
    for (double t = 1e-4; t < 1.0; t *= 1.07) {
        const uint32_t l = atlasLevelForTexel(256, 9, 0.5, t);
        if (l > 0) {
            EXPECT_LE(texel(l), t) << t;
        }
        if (l < 8) {
            EXPECT_GT(texel(l + 1), t) << t;
        }
    }
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, texel(3)), 3u);       // a texel exactly the map's is fine enough
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, 54.36 / 2048.0), 3u); // the meadow's first cascade: 2.65 cm
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, 1e-5), 0u);
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, 100.0), 8u); // clamped to the last level
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.0, 0.01), 0u);  // no plant height: the finest, not a cast of infinity
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, INFINITY), 8u);
    EXPECT_EQ(atlasLevelForTexel(256, 9, 0.5, NAN), 0u);
}

TEST(Atlas, MipsNeverBleedBetweenCells) {
    Atlas atlas;
    atlas.desc = {.cellWidth = 16, .cellHeight = 8, .rows = {{"a", {{}, {}, {}}}, {"b", {{}, {}}}}};
    const uint8_t colours[6][4] = {{255, 0, 0, 255},   {0, 255, 0, 255},  {0, 0, 255, 200},
                                   {200, 100, 30, 90}, {10, 20, 30, 255}, {0, 0, 0, 0}};
    AtlasMip& image = atlas.mips.emplace_back(AtlasMip{48, 16, std::vector<uint8_t>(48 * 16 * 4)});
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 48; ++x)
            std::copy_n(colours[(y / 8) * 3 + x / 16], 4, &image.rgba[(size_t(y) * 48 + x) * 4]);
    buildMipChain(atlas);
    ASSERT_EQ(atlas.mips.size(), 4u); // 8 -> 4 -> 2 -> 1 texel high cells
    for (uint32_t l = 1; l < atlas.mips.size(); ++l) {
        const AtlasMip& mip = atlas.mips[l];
        for (uint32_t y = 0; y < mip.height; ++y)
            for (uint32_t x = 0; x < mip.width; ++x) {
                const uint32_t cell = (y / (8 >> l)) * 3 + x / (16 >> l);
                const uint8_t* t = &mip.rgba[(size_t(y) * mip.width + x) * 4];
                for (int k = 0; k < 3; ++k) {
                    EXPECT_EQ(t[k], colours[cell][k]) << "level " << l << " cell " << cell;
                }
                EXPECT_EQ(t[3], colours[cell][3]) << "level " << l << " cell " << cell;
            }
    }
}
