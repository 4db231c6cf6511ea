#include "vegetation/atlas.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace sward;
using namespace sward::test;

namespace {

// Generating the full default atlas takes about a second; the tests share one copy.
const Atlas& defaultAtlas() {
    static const Atlas atlas = generateAtlas({});
    return atlas;
}

const Atlas& defaultAtlasWithMips(bool preserveCoverage) {
    static const Atlas preserved = [] {
        Atlas a = defaultAtlas();
        buildMipChain(a);
        return a;
    }();
    static const Atlas plain = [] {
        Atlas a = defaultAtlas();
        buildMipChain(a, 0.5f, false);
        return a;
    }();
    return preserveCoverage ? preserved : plain;
}

// A small atlas (2 rows of 32-texel cells) for tests that do not need the real one.
AtlasGenParams smallParams() {
    return {.seed = 7,
            .cellSize = 32,
            .rows = {{"grass", AtlasPlantKind::Grass, 2}, {"flowers", AtlasPlantKind::Flowers, 3}}};
}

struct MeanColour {
    double r = 0, g = 0, b = 0;
    size_t saturatedNonGreen = 0; // texels clearly red, yellow, white-ish or purple rather than green
};

MeanColour meanVisibleColour(const AtlasMip& mip, const AtlasRect& rect) {
    MeanColour m;
    size_t n = 0;
    for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
        for (uint32_t x = rect.x; x < rect.x + rect.width; ++x) {
            const uint8_t* t = &mip.rgba[(size_t(y) * mip.width + x) * 4];
            if (t[3] < 128) continue;
            m.r += t[0], m.g += t[1], m.b += t[2], ++n;
            const int r = t[0], g = t[1], b = t[2];
            const bool bright = std::max({r, g, b}) > 150;
            const bool notGreen = r > g + 30 || b > g + 30 || (r > 200 && g > 200 && b > 180);
            m.saturatedNonGreen += bright && notGreen;
        }
    if (n) m.r /= double(n), m.g /= double(n), m.b /= double(n);
    return m;
}

} // namespace

TEST(Atlas, DefaultLayoutFollowsTheVegetationCategories) {
    const AtlasDesc& desc = defaultAtlas().desc;
    ASSERT_EQ(desc.rows.size(), 3u);
    EXPECT_EQ(desc.rows[0].category, "ferns");
    EXPECT_EQ(desc.rows[1].category, "grass");
    EXPECT_EQ(desc.rows[2].category, "flowers");
    EXPECT_EQ(desc.rows[0].cells.size(), 4u);
    EXPECT_EQ(desc.rows[1].cells.size(), 8u);
    EXPECT_EQ(desc.rows[2].cells.size(), 8u);
    EXPECT_EQ(desc.cellWidth, 256u);
    EXPECT_EQ(desc.width(), 2048u);
    EXPECT_EQ(desc.height(), 768u);
    EXPECT_EQ(desc.mipLevelCount(), 9u);
    EXPECT_EQ(defaultAtlas().mips.size(), 1u);
    EXPECT_EQ(defaultAtlas().mips[0].rgba.size(), size_t(2048) * 768 * 4);
}

TEST(Atlas, VariantsOverrideGivesEveryRowThatManyColumns) {
    for (const AtlasRowSpec& row : defaultAtlasRows(3)) EXPECT_EQ(row.columns, 3u);
    EXPECT_EQ(atlasPlantKindForCategory("Tall grass"), AtlasPlantKind::Grass);
    EXPECT_EQ(atlasPlantKindForCategory("forest floor"), AtlasPlantKind::Ferns);
    EXPECT_EQ(atlasPlantKindForCategory("shrubs"), AtlasPlantKind::Flowers);
}

TEST(Atlas, CellRectsAndUvsTileTheImage) {
    const AtlasDesc& desc = defaultAtlas().desc;
    const AtlasRect r = desc.cellRect(2, 5, 3);
    EXPECT_EQ(r.x, 5u * 32u);
    EXPECT_EQ(r.y, 2u * 32u);
    EXPECT_EQ(r.width, 32u);
    const auto uv = desc.cellUvRect(1, 2);
    EXPECT_FLOAT_EQ(uv[0], 2.0f / 8.0f);
    EXPECT_FLOAT_EQ(uv[1], 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(uv[2], 3.0f / 8.0f);
    EXPECT_FLOAT_EQ(uv[3], 2.0f / 3.0f);
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
            EXPECT_GT(coverage, 0.10f) << "row " << r << " column " << c;
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

TEST(Atlas, GrassIsGreenAndFlowersHaveColouredHeads) {
    const Atlas& atlas = defaultAtlas();
    for (uint32_t c = 0; c < 8; ++c) {
        const MeanColour grass = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(1, c));
        EXPECT_GT(grass.g, grass.r) << "grass column " << c;
        EXPECT_GT(grass.g, grass.b * 1.5) << "grass column " << c;
        const MeanColour flowers = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(2, c));
        EXPECT_GT(flowers.saturatedNonGreen, 40u) << "flower column " << c;
    }
    for (uint32_t c = 0; c < 3; ++c) { // the fourth fern variant is autumn bracken
        const MeanColour fern = meanVisibleColour(atlas.mips[0], atlas.desc.cellRect(0, c));
        EXPECT_GT(fern.g, fern.r) << "fern column " << c;
    }
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

TEST(Atlas, SaveLoadRoundTripsExactly) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    saveAtlas(a, (dir / "a.png").string(), (dir / "a.json").string());
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png.tmp"));
    const Atlas b = loadAtlas((dir / "a.png").string(), (dir / "a.json").string());
    EXPECT_EQ(a.desc, b.desc);
    ASSERT_EQ(b.mips.size(), 1u);
    EXPECT_TRUE(a.mips[0] == b.mips[0]);
}

TEST(Atlas, LoadsMinimalUserDescription) {
    const auto dir = tempDir();
    writePng(dir / "user.png", 8, 4, 4, 8, std::vector<float>(8 * 4 * 4, 1.0f));
    std::ofstream(dir / "user.json")
        << R"({"cell_size": [4, 4], "base_v": 0.9, "rows": [{"category": "grass", "columns": 2}]})";
    const Atlas atlas = loadAtlas((dir / "user.png").string(), (dir / "user.json").string());
    ASSERT_EQ(atlas.desc.rows.size(), 1u);
    EXPECT_EQ(atlas.desc.rows[0].cells.size(), 2u);
    EXPECT_FLOAT_EQ(atlas.desc.rows[0].cells[1].baseV, 0.9f);
    EXPECT_FLOAT_EQ(atlas.desc.rows[0].cells[1].baseU, 0.5f);
}

TEST(Atlas, MipsKeepAlphaCoverage) {
    const Atlas& atlas = defaultAtlasWithMips(true);
    ASSERT_EQ(atlas.mips.size(), 9u);
    EXPECT_EQ(atlas.mips[8].width, 8u);
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
    // the reference, and distant grass would thin out. At 8x8 texel cells (level 5) plain box filtering loses over
    // a tenth of the grass row's coverage; MipsKeepAlphaCoverage shows the preserved chain does not.
    const Atlas& atlas = defaultAtlasWithMips(false);
    float base = 0.0f, level = 0.0f;
    for (uint32_t c = 0; c < 8; ++c) {
        base += alphaCoverage(atlas.mips[0], atlas.desc.cellRect(1, c, 0), 0.5f);
        level += alphaCoverage(atlas.mips[5], atlas.desc.cellRect(1, c, 5), 0.5f);
    }
    EXPECT_LT(level, 0.9f * base);
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

TEST(Atlas, MissingFilesAreNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    saveAtlas(a, (dir / "a.png").string(), (dir / "a.json").string());
    expectError([&] { loadAtlas((dir / "a.png").string(), (dir / "none.json").string()); }, {"none.json", "missing"});
    expectError([&] { loadAtlas((dir / "none.png").string(), (dir / "a.json").string()); }, {"none.png"});
}

TEST(Atlas, BadJsonIsNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    const std::string png = (dir / "a.png").string(), json = (dir / "a.json").string();
    saveAtlas(a, png, json);
    std::ofstream(json) << "{\"cell_size\": [32, 32], ";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "not valid JSON"});
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2}], "colour": 1})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "unknown key 'colour'"});
    std::ofstream(json) << R"({"cell_size": [30, 32], "rows": [{"category": "grass", "columns": 2}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "powers of two"});
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2, "cells": []}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "one entry per column"});
}

TEST(Atlas, ImageNotMatchingTheGridIsNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    const std::string png = (dir / "a.png").string(), json = (dir / "a.json").string();
    saveAtlas(a, png, json);
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.png", "96x64", "64x32"});
}

TEST(Atlas, ImageThatIsNotRgba8IsNamed) {
    const auto dir = tempDir();
    const std::string json = (dir / "a.json").string();
    std::ofstream(json) << R"({"cell_size": [4, 4], "rows": [{"category": "grass", "columns": 1}]})";
    writePng(dir / "rgb.png", 4, 4, 3, 8, std::vector<float>(4 * 4 * 3, 0.5f));
    expectError([&] { loadAtlas((dir / "rgb.png").string(), json); }, {"rgb.png", "8-bit RGBA"});
    writePng(dir / "wide.png", 4, 4, 4, 16, std::vector<float>(4 * 4 * 4, 0.5f));
    expectError([&] { loadAtlas((dir / "wide.png").string(), json); }, {"wide.png", "8-bit RGBA"});
}

TEST(Atlas, InvalidGenerationParametersAreRejected) {
    AtlasGenParams p = smallParams();
    p.cellSize = 100;
    expectError([&] { generateAtlas(p); }, {"cell size 100"});
    p = smallParams();
    p.rows[0].columns = 0;
    expectError([&] { generateAtlas(p); }, {"grass", "1..64"});
}
