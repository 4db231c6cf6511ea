// Land cover -> grass map (issue 15): the table, the WorldCover preset, soft borders, and the plant counts that a
// land-cover map gives through placement.
#include "vegetation/land_cover.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

using namespace sward;
using namespace sward::test;

namespace {

constexpr int64_t kTree = 10, kShrub = 20, kGrass = 30, kBuilt = 50, kSnow = 70, kWater = 80;

// A width x height raster of class codes code(x, y), top row first.
RasterBand codes(uint32_t width, uint32_t height, const std::function<double(uint32_t, uint32_t)>& code) {
    RasterBand raster{.width = width, .height = height, .source = "codes.tif"};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) raster.values.push_back(code(x, y));
    return raster;
}

LandCoverParams worldCover(double border) {
    return {.table = esaWorldCoverTable(), .borderWidth = border};
}

// Channel c of pixel (x, y).
float at(const GrassMap& map, uint32_t x, uint32_t y, uint32_t c) {
    return map.values()[(size_t(y) * map.width() + x) * map.channels() + c];
}

} // namespace

TEST(LandCoverTable, FindsTheCodesItHoldsAndNoOthers) {
    LandCoverTable table;
    table.classes[7] = {0.1f, 0.2f, 0.3f, 0.0f};
    ASSERT_NE(table.find(7), nullptr);
    EXPECT_EQ(*table.find(7), glm::vec4(0.1f, 0.2f, 0.3f, 0.0f));
    EXPECT_EQ(table.find(8), nullptr);
    EXPECT_EQ(table.find(-7), nullptr);
}

TEST(LandCoverTable, WorldCoverPresetHoldsTheElevenClasses) {
    const LandCoverTable t = esaWorldCoverTable();
    std::vector<int64_t> keys;
    for (const auto& entry : t.classes) keys.push_back(entry.first);
    EXPECT_EQ(keys, (std::vector<int64_t>{10, 20, 30, 40, 50, 60, 70, 80, 90, 95, 100}));
    EXPECT_EQ(t.channels, 3u);
    for (int64_t bare : {kBuilt, kSnow, kWater}) EXPECT_EQ(*t.find(bare), glm::vec4(0.0f)) << bare;
    EXPECT_EQ(t.find(kGrass)->g, 1.0f);              // grassland: the full meadow
    EXPECT_GT(t.find(kTree)->r, t.find(kTree)->g);   // tree cover: forest floor over grass
    EXPECT_GT(t.find(kShrub)->b, t.find(kGrass)->b); // shrubland: more shrubs than grassland
    EXPECT_LT(t.find(60)->g, 0.2f);                  // bare / sparse: under a fifth of the grass
    for (const auto& [code, v] : t.classes) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(v, glm::vec4(0.0f))) &&
                    glm::all(glm::lessThanEqual(v, glm::vec4(1.0f))))
            << code;
        EXPECT_EQ(v.a, 0.0f) << code;
    }
}

TEST(LandCover, HardBordersGiveEveryPixelItsClassIntensities) {
    const RasterBand raster = codes(4, 3, [](uint32_t x, uint32_t y) { return (x + y) % 2 ? kTree : 95; });
    const GrassMap map = makeLandCoverGrassMap(raster, worldCover(0.0), {1.0, 1.0}, "test");
    ASSERT_EQ(map.width(), 4u);
    ASSERT_EQ(map.height(), 3u);
    ASSERT_EQ(map.channels(), 3u);
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 0; x < 4; ++x) {
            const glm::vec4 expected = *esaWorldCoverTable().find(int64_t(raster.at(x, y)));
            for (uint32_t c = 0; c < 3; ++c) ASSERT_EQ(at(map, x, y, c), expected[int(c)]);
        }
    EXPECT_EQ(map.source(), "codes.tif");
}

// A straight north-south border at x = 20 m between grassland (west) and shrubland (east), 1 m pixels, border 8 m:
// the box of pixel i (centre i + 0.5) reaches (i + 4.5 - 20) / 8 into the shrubland, so grass falls linearly from
// 1 to 0.4 over pixels 16..23 and is exactly each class's value beyond.
TEST(LandCover, SoftBorderRampsLinearlySymmetricallyAndMonotonically) {
    const RasterBand raster = codes(40, 5, [](uint32_t x, uint32_t) { return x < 20 ? kGrass : kShrub; });
    const GrassMap map = makeLandCoverGrassMap(raster, worldCover(8.0), {1.0, 1.0}, "test");
    const glm::vec4 west = *esaWorldCoverTable().find(kGrass), east = *esaWorldCoverTable().find(kShrub);
    for (uint32_t x = 0; x < 40; ++x) {
        const double shrub = std::clamp((x + 4.5 - 20.0) / 8.0, 0.0, 1.0);
        for (uint32_t c = 0; c < 3; ++c) {
            const double expected = double(west[int(c)]) + (double(east[int(c)]) - double(west[int(c)])) * shrub;
            EXPECT_NEAR(at(map, x, 2, c), expected, 1e-6) << "x " << x << " channel " << c;
            for (uint32_t y = 0; y < 5; ++y) ASSERT_EQ(at(map, x, y, c), at(map, x, 2, c)); // the border is straight
        }
        const float grass = at(map, x, 0, 1), shrubs = at(map, x, 0, 2);
        EXPECT_TRUE(x >= 16 || grass == west.g) << x; // bitwise: the box holds grassland only
        EXPECT_TRUE(x <= 23 || grass == east.g) << x;
        EXPECT_TRUE(x == 0 || grass <= at(map, x - 1, 0, 1)) << x;  // grass falls monotonically
        EXPECT_TRUE(x == 0 || shrubs >= at(map, x - 1, 0, 2)) << x; // shrubs rise
    }
    for (uint32_t d = 0; d < 20; ++d) // mirror images about the border sum to both classes
        EXPECT_NEAR(at(map, 19 - d, 0, 1) + at(map, 20 + d, 0, 1), west.g + east.g, 1e-6) << d;
    EXPECT_LT(at(map, 19, 0, 1), west.g);
    EXPECT_GT(at(map, 20, 0, 1), east.g);
}

TEST(LandCover, BorderWidthIsInMetresWhateverThePixelSize) {
    // The same 8 m border over 2 m pixels: the ramp spans 4 pixels instead of 8.
    const RasterBand raster = codes(20, 1, [](uint32_t x, uint32_t) { return x < 10 ? kGrass : kShrub; });
    const GrassMap map = makeLandCoverGrassMap(raster, worldCover(8.0), {2.0, 2.0}, "test");
    EXPECT_EQ(at(map, 7, 0, 1), 1.0f);
    EXPECT_LT(at(map, 8, 0, 1), 1.0f);
    EXPECT_GT(at(map, 11, 0, 1), 0.4f);
    EXPECT_EQ(at(map, 12, 0, 1), 0.4f);
}

TEST(LandCover, FarFromEveryBorderTheMapIsBitwiseTheHardMap) {
    // Patches of four classes; a pixel whose 6 m box (plus its own pixel) holds one class keeps its exact values.
    const auto code = [](uint32_t x, uint32_t y) {
        return std::array<int64_t, 4>{10, 20, 30, 90}[(x / 13 + 2 * (y / 11)) % 4];
    };
    const RasterBand raster = codes(52, 44, code);
    const GrassMap soft = makeLandCoverGrassMap(raster, worldCover(6.0), {1.0, 1.0}, "test");
    const GrassMap hard = makeLandCoverGrassMap(raster, worldCover(0.0), {1.0, 1.0}, "test");
    uint32_t interior = 0, blended = 0;
    for (uint32_t y = 0; y < 44; ++y)
        for (uint32_t x = 0; x < 52; ++x) {
            bool single = true;
            for (int dy = -3; dy <= 3; ++dy)
                for (int dx = -3; dx <= 3; ++dx) {
                    const int xx = std::clamp(int(x) + dx, 0, 51), yy = std::clamp(int(y) + dy, 0, 43);
                    single = single && code(uint32_t(xx), uint32_t(yy)) == code(x, y);
                }
            for (uint32_t c = 0; c < 3; ++c)
                ASSERT_TRUE(!single || at(soft, x, y, c) == at(hard, x, y, c)) << x << "," << y;
            interior += single;
            blended += !single && at(soft, x, y, 1) != at(hard, x, y, 1);
        }
    EXPECT_GT(interior, 500u);
    EXPECT_GT(blended, 500u);
}

TEST(LandCover, SameMapOnEveryRunAndForAnyThreadCount) {
    const RasterBand raster = codes(97, 61, [](uint32_t x, uint32_t y) {
        return std::array<int64_t, 5>{10, 20, 30, 40, 60}[(x * 7 + y * 3 + x * y) / 17 % 5];
    });
    const GrassMap one = makeLandCoverGrassMap(raster, worldCover(7.5), {0.7, 1.3}, "test", 1);
    EXPECT_EQ(one.values(), makeLandCoverGrassMap(raster, worldCover(7.5), {0.7, 1.3}, "test", 1).values());
    EXPECT_EQ(one.values(), makeLandCoverGrassMap(raster, worldCover(7.5), {0.7, 1.3}, "test", 4).values());
}

TEST(LandCover, NodataPixelsAreBareUnlessGivenAClass) {
    RasterBand raster = codes(3, 1, [](uint32_t x, uint32_t) { return x == 1 ? 255.0 : double(kGrass); });
    raster.nodata = 255.0;
    LandCoverParams params = worldCover(0.0);
    EXPECT_EQ(at(makeLandCoverGrassMap(raster, params, {1, 1}, "test"), 1, 0, 1), 0.0f);
    params.nodataCode = kShrub;
    EXPECT_EQ(at(makeLandCoverGrassMap(raster, params, {1, 1}, "test"), 1, 0, 1), 0.4f);
    EXPECT_EQ(at(makeLandCoverGrassMap(raster, params, {1, 1}, "test"), 0, 0, 1), 1.0f);
}

TEST(LandCover, AClassFeedingAlphaMakesAFourChannelMap) {
    LandCoverParams params{.borderWidth = 0.0};
    params.table.classes = {{1, {0.0f, 0.0f, 0.0f, 0.5f}}, {2, {1.0f, 0.0f, 0.0f, 0.0f}}};
    params.table.channels = 4;
    const GrassMap map =
        makeLandCoverGrassMap(codes(2, 1, [](uint32_t x, uint32_t) { return x + 1.0; }), params, {1, 1}, "test");
    ASSERT_EQ(map.channels(), 4u);
    EXPECT_EQ(map.values(), (std::vector<float>{0, 0, 0, 0.5f, 1, 0, 0, 0}));
}

TEST(LandCover, LoadsAPngOfClassCodesOverTheTile) {
    SWARD_SKIP_WITHOUT(Gdal); // land-cover rasters are read through GDAL, PNG too
    const auto path = tempDir() / "cover.png";
    writePng(path, 2, 1, 1, 8, {float(kTree) / 255.0f, float(kWater) / 255.0f});
    LandCoverParams params = worldCover(5.0);
    params.file = path.string();
    const GrassMap map = loadLandCoverGrassMap(params, 20.0, "test"); // 10 m pixels: a 5 m border stays inside
    EXPECT_EQ(map.values(), (std::vector<float>{0.8f, 0.15f, 0.2f, 0, 0, 0}));
    EXPECT_EQ(map.source(), path.string());
}

TEST(LandCoverErrors, CodeMissingFromTheTableNamesCodePixelAndKey) {
    const RasterBand raster = codes(5, 4, [](uint32_t x, uint32_t y) { return x >= 3 && y >= 2 ? 42.0 : 30.0; });
    expectError(
        [&] {
            makeLandCoverGrassMap(raster, worldCover(5.0), {1, 1}, "s.json: 'land_cover'");
        },
        {"s.json: 'land_cover': class code 42 of raster 'codes.tif' (first at pixel (3, 2)) is not in the "
         "table (it has 10, 20, 30, 40, 50, 60, 70, 80, 90, 95, 100)"});
}

TEST(LandCoverErrors, ValueThatIsNotAClassCodeNamesThePixel) {
    for (double bad : {10.5, -10.0, 5e9, std::numeric_limits<double>::quiet_NaN()}) {
        const RasterBand raster = codes(2, 2, [&](uint32_t x, uint32_t y) { return x == 1 && y == 1 ? bad : 30.0; });
        expectError(
            [&] {
                makeLandCoverGrassMap(raster, worldCover(0.0), {1, 1}, "key");
            },
            {"key: raster 'codes.tif'", "pixel (1, 1)", "not a class code"});
    }
}

TEST(LandCoverErrors, NodataCodeMustBeInTheTable) {
    LandCoverParams params = worldCover(0.0);
    params.nodataCode = 0;
    expectError(
        [&] {
            makeLandCoverGrassMap(codes(1, 1, [](uint32_t, uint32_t) { return 30.0; }), params, {1, 1}, "key");
        },
        {"key: the nodata class code 0 is not in the table"});
}

// Acceptance (issue 15): "land-cover table gives the expected category densities (counted)". A 100 m tile whose
// west half is grassland and east half shrubland (20 x 20 pixels of 5 m, border 10 m) is placed on flat ground;
// the plants of each category are counted in the 40 m strips away from the border.
// Expected: density x intensity x 4000 m^2. Placement rounds each cluster's expected count I (exact here: the map
// is constant over the strips) to floor(I + u) with a hashed uniform u, independently per cluster and category,
// so each of the 160 clusters of a strip is off by less than 1 with mean 0 and variance at most 1/4: the strip's
// count has a standard deviation of at most sqrt(160) / 2 = 6.3 plants, and 5 of them (32 plants) is the tolerance.
TEST(LandCover, TableGivesTheExpectedCategoryDensitiesCounted) {
    const RasterBand raster = codes(20, 20, [](uint32_t x, uint32_t) { return x < 10 ? kGrass : kShrub; });
    const GrassMap map = makeLandCoverGrassMap(raster, worldCover(10.0), {5.0, 5.0}, "test");
    VegetationParams params;
    params.tileSize = 100.0f;
    params.seed = 11;
    const Ground flat(Heightfield(2, 2, 100.0f, glm::vec2(0.0f), {0, 0, 0, 0}));
    const VegetationTile tile = generateTile(flat, map, params, {}, 2);
    uint64_t west[3] = {}, east[3] = {}, middle = 0;
    for (const FieldVegetation& field : tile.fields)
        for (const gpu::PlantStatic& r : field.staticRecords) {
            const glm::vec3 p = decodePlantPosition(r, field.origin, field.positionStep);
            const uint32_t category = decodePlantStatic(r).category;
            if (p.x < 40.0f)
                ++west[category];
            else if (p.x >= 60.0f)
                ++east[category];
            else
                ++middle;
        }
    const double area = 40.0 * 100.0, tolerance = 5.0 * std::sqrt(160.0) / 2.0;
    const glm::vec4 grassland = *esaWorldCoverTable().find(kGrass), shrubland = *esaWorldCoverTable().find(kShrub);
    for (uint32_t c = 0; c < 3; ++c) {
        const double density = params.categories[c].density;
        EXPECT_NEAR(double(west[c]), density * grassland[int(c)] * area, tolerance) << "category " << c;
        EXPECT_NEAR(double(east[c]), density * shrubland[int(c)] * area, tolerance) << "category " << c;
    }
    EXPECT_GT(west[1], 60000u); // grassland: 16 grass plants per m^2
    EXPECT_GT(east[2], 3900u);  // shrubland: 1 shrub or flower per m^2
    EXPECT_GT(middle, 0u);
}
