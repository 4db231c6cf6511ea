// The built-in procedural atlas (vegetation/atlas_paint.cpp, atlas_plants.cpp).
#include "vegetation/atlas.h"

#include "atlas_fixtures.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace sward;
using namespace sward::test;

namespace {

struct MeanColour {
    double r = 0, g = 0, b = 0;
    double saturation = 0; // mean HSV saturation of the visible texels (sRGB)
    double notGreen = 0;   // share of visible texels with red >= green: straw, brown, yellow or red
    size_t petalLike = 0;  // bright texels that are not green: white, yellow, red, purple or blue petals
};

MeanColour meanVisibleColour(const AtlasMip& mip, const AtlasRect& rect) {
    MeanColour m;
    size_t n = 0;
    for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
        for (uint32_t x = rect.x; x < rect.x + rect.width; ++x) {
            const uint8_t* t = &mip.rgba[(size_t(y) * mip.width + x) * 4];
            if (t[3] < 128) continue;
            m.r += t[0], m.g += t[1], m.b += t[2], ++n;
            const int r = t[0], g = t[1], b = t[2], hi = std::max({r, g, b}), lo = std::min({r, g, b});
            m.saturation += hi > 0 ? double(hi - lo) / double(hi) : 0.0;
            m.notGreen += r >= g;
            m.petalLike += hi > 140 && (r >= g || b > g);
        }
    if (n) m.r /= double(n), m.g /= double(n), m.b /= double(n), m.saturation /= double(n), m.notGreen /= double(n);
    return m;
}

} // namespace

TEST(Atlas, DefaultLayoutFollowsTheVegetationCategories) {
    const AtlasDesc& desc = defaultAtlas().desc;
    ASSERT_EQ(desc.rows.size(), 3u);
    EXPECT_EQ(desc.rows[0].category, "ferns");
    EXPECT_EQ(desc.rows[1].category, "grass");
    EXPECT_EQ(desc.rows[2].category, "flowers");
    EXPECT_EQ(desc.rows[0].cells.size(), 8u);
    EXPECT_EQ(desc.rows[1].cells.size(), 12u);
    EXPECT_EQ(desc.rows[2].cells.size(), 8u);
    EXPECT_EQ(desc.cellWidth, 256u);
    EXPECT_EQ(desc.width(), 3072u);
    EXPECT_EQ(desc.height(), 768u);
    EXPECT_EQ(desc.mipLevelCount(), 9u);
    EXPECT_EQ(defaultAtlas().mips.size(), 1u);
    EXPECT_EQ(defaultAtlas().mips[0].rgba.size(), size_t(3072) * 768 * 4);
}

TEST(Atlas, VariantsOverrideGivesEveryRowThatManyColumns) {
    for (const AtlasRowSpec& row : defaultAtlasRows(3)) EXPECT_EQ(row.columns, 3u);
    EXPECT_EQ(atlasPlantKindForCategory("Tall grass"), AtlasPlantKind::Grass);
    EXPECT_EQ(atlasPlantKindForCategory("forest floor"), AtlasPlantKind::Ferns);
    EXPECT_EQ(atlasPlantKindForCategory("shrubs"), AtlasPlantKind::Flowers);
}

TEST(Atlas, GenerationIsDeterministic) {
    const Atlas a = generateAtlas(smallParams()), b = generateAtlas(smallParams());
    EXPECT_EQ(a.desc, b.desc);
    EXPECT_TRUE(a.mips[0] == b.mips[0]);
    EXPECT_TRUE(generateAtlas({}).mips[0] == defaultAtlas().mips[0]);
}

TEST(Atlas, SeedChangesThePlants) {
    AtlasGenParams other = smallParams();
    other.seed = 8;
    EXPECT_FALSE(generateAtlas(smallParams()).mips[0] == generateAtlas(other).mips[0]);
}

TEST(Atlas, EveryCellHasPlausibleCoverage) {
    const Atlas& atlas = defaultAtlas();
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) {
            const float coverage = alphaCoverage(atlas.mips[0], atlas.desc.cellRect(r, c), 0.5f);
            // Thin blades and flower heads that are a small share of the plant: 0.07..0.32 in the default atlas.
            EXPECT_GT(coverage, 0.05f) << "row " << r << " column " << c;
            EXPECT_LT(coverage, 0.80f) << "row " << r << " column " << c;
        }
}

TEST(Atlas, CellsKeepAnEmptyBorderAtTopAndSides) {
    // Plants stay inside their cell, so bilinear filtering near a cell edge does not pick up the neighbour.
    const Atlas& atlas = defaultAtlas();
    const AtlasMip& image = atlas.mips[0];
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) {
            const AtlasRect rect = atlas.desc.cellRect(r, c);
            uint32_t maxAlpha = 0;
            for (uint32_t i = 0; i < rect.width; ++i) {
                auto alpha = [&](uint32_t x, uint32_t y) { return image.rgba[(size_t(y) * image.width + x) * 4 + 3]; };
                maxAlpha = std::max<uint32_t>({maxAlpha, alpha(rect.x + i, rect.y), alpha(rect.x, rect.y + i),
                                               alpha(rect.x + rect.width - 1, rect.y + i)});
            }
            EXPECT_EQ(maxAlpha, 0u) << "row " << r << " column " << c;
        }
}

// Plant albedos are those of real vegetation (vegetation/atlas_plants.cpp): the old saturated palette measured a
// mean texel saturation of 0.63-0.74 in grass and ferns, the measured albedos 0.37-0.45.
TEST(Atlas, GrassIsDesaturatedGreenWithDryBladesInEveryVariant) {
    const Atlas& atlas = defaultAtlas();
    for (uint32_t c = 0; c < atlas.desc.rows[1].cells.size(); ++c) {
        const MeanColour grass = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(1, c));
        EXPECT_GT(grass.g, grass.r) << "grass column " << c;
        EXPECT_GT(grass.g, grass.b * 1.3) << "grass column " << c;
        EXPECT_LT(grass.saturation, 0.5) << "grass column " << c;
        EXPECT_GT(grass.saturation, 0.15) << "grass column " << c; // not grey either
        // Straw, yellowed and dead blades: a share of every clump, never most of it.
        EXPECT_GT(grass.notGreen, 0.05) << "grass column " << c;
        EXPECT_LT(grass.notGreen, 0.6) << "grass column " << c;
    }
}

TEST(Atlas, FernsAreGreenInEveryVariant) {
    const Atlas& atlas = defaultAtlas();
    for (uint32_t c = 0; c < atlas.desc.rows[0].cells.size(); ++c) {
        const MeanColour fern = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(0, c));
        EXPECT_GT(fern.g, fern.r * 1.15) << "fern column " << c;
        EXPECT_LT(fern.notGreen, 0.1) << "fern column " << c; // only the dead leaves at the base; no bracken
        EXPECT_LT(fern.saturation, 0.5) << "fern column " << c;
    }
}

TEST(Atlas, FlowersHavePetalsOnGreenPlants) {
    const Atlas& atlas = defaultAtlas();
    for (uint32_t c = 0; c < atlas.desc.rows[2].cells.size(); ++c) {
        const MeanColour flowers = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(2, c));
        EXPECT_GT(flowers.petalLike, 40u) << "flower column " << c;
        // The heads are a small share of the plant: most texels are stem and leaf.
        EXPECT_LT(flowers.notGreen, 0.4) << "flower column " << c;
    }
}

TEST(Atlas, InvalidGenerationParametersAreRejected) {
    AtlasGenParams p = smallParams();
    p.cellSize = 100;
    expectError([&] { generateAtlas(p); }, {"cell size 100"});
    p = smallParams();
    p.rows[0].columns = 0;
    expectError([&] { generateAtlas(p); }, {"grass", "1..64"});
}
