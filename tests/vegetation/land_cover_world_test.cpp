// Land cover over a world of tiles (issue 51): each tile's grass map from the raster's window over the tile, bitwise
// the whole raster's map cut at the tile; the raster's grid checked against the world; no plant doubled or missing
// across a tile border.
#include "vegetation/land_cover.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

using namespace sward;
using namespace sward::test;

namespace {

constexpr int64_t kTree = 10, kShrub = 20, kGrass = 30, kCrop = 40, kWater = 80;

// A width x height raster of class codes code(x, y), top row first.
RasterBand codes(uint32_t width, uint32_t height, const std::function<double(uint32_t, uint32_t)>& code) {
    RasterBand raster{.width = width, .height = height, .source = "codes.tif"};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) raster.values.push_back(code(x, y));
    return raster;
}

// Patches of five classes and single odd pixels: every kind of border a box can straddle.
RasterBand patchwork(uint32_t width, uint32_t height) {
    return codes(width, height, [](uint32_t x, uint32_t y) {
        const int64_t classes[] = {kTree, kShrub, kGrass, kCrop, kWater};
        const uint32_t h = (x / 3 * 7 + y / 4 * 13 + (x * y) % 5) % 5;
        return double(classes[(x + y) % 11 == 0 ? (h + 2) % 5 : h]);
    });
}

RasterBand cut(const RasterBand& raster, RasterWindow w) {
    RasterBand out{.width = w.width, .height = w.height, .nodata = raster.nodata, .source = raster.source};
    for (uint32_t y = w.row; y < w.row + w.height; ++y)
        for (uint32_t x = w.column; x < w.column + w.width; ++x) out.values.push_back(raster.at(x, y));
    return out;
}

std::vector<float> cutMap(const GrassMap& map, RasterWindow w) {
    std::vector<float> out;
    for (uint32_t y = w.row; y < w.row + w.height; ++y)
        for (uint32_t x = w.column; x < w.column + w.width; ++x)
            for (uint32_t c = 0; c < map.channels(); ++c)
                out.push_back(map.values()[(size_t(y) * map.width() + x) * map.channels() + c]);
    return out;
}

LandCoverParams worldCover(double border) {
    return {.table = esaWorldCoverTable(), .borderWidth = border};
}

} // namespace

// A 24 x 16 raster over 3 x 2 tiles of 16 m (8 x 8 pixels of 2 m): every tile's map, made from its window alone,
// equals the whole raster's map cut at the tile bit for bit, for borders inside a pixel, across a few pixels and
// wider than the raster (the clipping at the raster's edge included); and the whole raster's map agrees with the
// one-tile computation (separable prefix sums, another order of additions) to float rounding.
TEST(LandCoverWorld, TileMapFromItsWindowEqualsTheWholeRastersMapCutAtTheTile) {
    const RasterBand raster = patchwork(24, 16);
    const LandCoverWorld world{.tilesX = 3, .tilesY = 2, .tileSize = 16.0};
    const LandCoverGrid grid = landCoverGrid(24, 16, std::nullopt, "codes.tif", world, "test");
    ASSERT_EQ(grid.pixelsPerTile, glm::uvec2(8, 8));
    ASSERT_EQ(grid.pixelSize, glm::dvec2(2.0, 2.0));
    const RasterWindow all{.width = 24, .height = 16};
    for (double border : {0.0, 1.5, 7.0, 13.0, 100.0}) {
        const LandCoverParams params = worldCover(border);
        const GrassMap whole = makeLandCoverWindowGrassMap(raster, all, {24, 16}, all, params, grid.pixelSize, "test");
        const GrassMap reference = makeLandCoverGrassMap(raster, params, grid.pixelSize, "test");
        ASSERT_EQ(whole.values().size(), reference.values().size());
        for (size_t i = 0; i < whole.values().size(); ++i)
            ASSERT_NEAR(whole.values()[i], reference.values()[i], 1e-6) << "border " << border << " value " << i;
        if (border == 0.0) {
            EXPECT_EQ(whole.values(), reference.values()); // every pixel its class, exactly
        }
        size_t narrower = 0;
        for (uint32_t ty = 0; ty < 2; ++ty)
            for (uint32_t tx = 0; tx < 3; ++tx) {
                const RasterWindow where = landCoverTileWindow(grid, {tx, ty}, border);
                narrower += where.width < 24 || where.height < 16;
                const RasterWindow tile{.column = tx * 8, .row = (1 - ty) * 8, .width = 8, .height = 8};
                const GrassMap map = makeLandCoverWindowGrassMap(cut(raster, where), where, {24, 16}, tile, params,
                                                                 grid.pixelSize, "test");
                ASSERT_EQ(map.width(), 8u);
                ASSERT_EQ(map.height(), 8u);
                EXPECT_EQ(map.values(), cutMap(whole, tile)) << "border " << border << " tile " << tx << ", " << ty;
            }
        if (border <= 7.0) {
            EXPECT_EQ(narrower, 6u) << border; // the windows are windows, not the raster
        }
    }
}

TEST(LandCoverWorld, WindowMapIsTheSameForAnyThreadCount) {
    const RasterBand raster = patchwork(24, 16);
    const RasterWindow all{.width = 24, .height = 16}, out{.column = 3, .row = 2, .width = 17, .height = 11};
    const GrassMap one = makeLandCoverWindowGrassMap(raster, all, {24, 16}, out, worldCover(9.0), {2, 2}, "test", 1);
    for (uint32_t threads : {2u, 3u, 8u})
        EXPECT_EQ(
            makeLandCoverWindowGrassMap(raster, all, {24, 16}, out, worldCover(9.0), {2, 2}, "test", threads).values(),
            one.values())
            << threads;
}

TEST(LandCoverWorld, BoxHoldingOneClassGivesExactlyItsIntensities) {
    const RasterBand raster = codes(12, 4, [](uint32_t x, uint32_t) { return x < 6 ? kGrass : kShrub; });
    const RasterWindow all{.width = 12, .height = 4};
    const GrassMap map = makeLandCoverWindowGrassMap(raster, all, {12, 4}, all, worldCover(4.0), {1, 1}, "test");
    const glm::vec4 grass = *esaWorldCoverTable().find(kGrass), shrub = *esaWorldCoverTable().find(kShrub);
    for (uint32_t c = 0; c < 3; ++c) {
        EXPECT_EQ(cutMap(map, {.column = 3, .row = 2, .width = 1, .height = 1})[c], grass[int(c)]); // box 1.5 .. 5.5
        EXPECT_EQ(cutMap(map, {.column = 8, .row = 2, .width = 1, .height = 1})[c], shrub[int(c)]);
        const float middle = cutMap(map, {.column = 5, .row = 2, .width = 1, .height = 1})[c]; // box 3.5 .. 7.5
        EXPECT_NEAR(middle, (2.5f * grass[int(c)] + 1.5f * shrub[int(c)]) / 4.0f, 1e-6f);
    }
}

TEST(LandCoverWorld, ErrorsNameTheRasterPixelInTheWholeRaster) {
    RasterBand raster = patchwork(24, 16);
    raster.values[size_t(13) * 24 + 19] = 42.0; // pixel (19, 13)
    const LandCoverWorld world{.tilesX = 3, .tilesY = 2, .tileSize = 16.0};
    const LandCoverGrid grid = landCoverGrid(24, 16, std::nullopt, "codes.tif", world, "test");
    const RasterWindow where = landCoverTileWindow(grid, {2, 0}, 5.0);
    expectError(
        [&] {
            makeLandCoverWindowGrassMap(cut(raster, where), where, {24, 16}, {16, 8, 8, 8}, worldCover(5.0),
                                        grid.pixelSize, "s.json: 'land_cover'");
        },
        {"s.json: 'land_cover': class code 42 of raster 'codes.tif' (first at pixel (19, 13))"});
}

TEST(LandCoverWorld, GridStretchesAnUngeoreferencedRasterAndChecksAGeoreferencedOne) {
    const LandCoverWorld world{.tilesX = 4, .tilesY = 2, .tileSize = 500.0};
    const LandCoverGrid stretched = landCoverGrid(400, 100, std::nullopt, "c.tif", world, "test");
    EXPECT_EQ(stretched.pixelsPerTile, glm::uvec2(100, 50));
    EXPECT_EQ(stretched.pixelSize, glm::dvec2(5.0, 10.0));
    const RasterGeoTransform utm{
        .originX = 500000, .originY = 4100000, .pixelWidth = 10, .pixelHeight = 10, .metresPerUnit = 1.0};
    EXPECT_EQ(landCoverGrid(200, 100, utm, "c.tif", world, "test").pixelsPerTile, glm::uvec2(50, 50));
    // A larger area's raster: its own 10 m pixels, the world cut at its south-west corner.
    const LandCoverGrid larger = landCoverGrid(230, 120, utm, "c.tif", world, "test");
    EXPECT_EQ(larger.pixelsPerTile, glm::uvec2(50, 50));
    const RasterWindow window = landCoverTileWindow(larger, {0, 0}, 0.0); // tile (0, 0): the bottom-left 50 x 50
    EXPECT_EQ(window.column, 0u);
    EXPECT_EQ(window.row + window.height, 120u);
    EXPECT_EQ(landCoverTileWindow(larger, {3, 1}, 0.0).row, 19u); // 120 - 100 - 1 (margin)
    RasterGeoTransform feet = utm;
    feet.pixelWidth = feet.pixelHeight = 10.0 / 0.3048;
    feet.metresPerUnit = 0.3048;
    EXPECT_EQ(landCoverGrid(200, 100, feet, "c.tif", world, "test").pixelSize, glm::dvec2(10.0, 10.0));
    RasterGeoTransform degrees = utm;
    degrees.pixelWidth = degrees.pixelHeight = 1.0 / 12000.0;
    degrees.metresPerUnit = 0.0; // no linear unit: stretched, as one tile's land cover is over its tile
    EXPECT_EQ(landCoverGrid(200, 100, degrees, "c.tif", world, "test").pixelSize, glm::dvec2(10.0, 10.0));
    expectError([&] { landCoverGrid(190, 100, utm, "c.tif", world, "s.json: 'land_cover'"); },
                {"s.json: 'land_cover': raster 'c.tif' covers 1900 x 1000 m (190 x 100 pixels of 10 x 10 m), but the "
                 "world covers 2000 x 1000 m (4 x 2 tiles of 500 m)",
                 "must cover the world's extent"});
    RasterGeoTransform coarse = utm;
    coarse.pixelWidth = coarse.pixelHeight = 30.0;
    expectError([&] { landCoverGrid(100, 100, coarse, "c.tif", world, "key"); },
                {"key: raster 'c.tif' has pixels of 30 x 30 m, which do not divide the world's tiles of 500 m"});
    expectError([&] { landCoverGrid(402, 100, std::nullopt, "c.tif", world, "key"); },
                {"key: raster 'c.tif' has 402 x 100 pixels, not a whole number of pixels per tile", "4 x 2 tiles"});
}

// Acceptance (issue 51): no plant doubled or missing across a tile border. Two neighbouring 50 m tiles of one
// grassland raster (10 x 5 pixels of 10 m), each placed from its own window's map on flat ground; the grass plants
// of both tiles are counted by position in 2 m strips on either side of the border and in the tiles' interiors. A
// strip of 2 x 46 m holds about 1470 grass plants, so its density is within a few per cent of the interior's unless
// a tile places plants beyond its square (doubled: ratio 2) or leaves its edge bare (missing: ratio 0).
TEST(LandCoverWorld, BorderStripsHoldTheInteriorsPlantDensity) {
    constexpr double kTile = 50.0, kStrip = 2.0;
    const RasterBand raster = codes(10, 5, [](uint32_t, uint32_t) { return double(kGrass); });
    const LandCoverWorld world{.tilesX = 2, .tilesY = 1, .tileSize = kTile};
    const LandCoverGrid grid = landCoverGrid(10, 5, std::nullopt, "codes.tif", world, "test");
    VegetationParams params;
    params.tileSize = float(kTile);
    params.seed = 5;
    params.worldOrigin = glm::vec2(-50.0f, 100.0f);
    const glm::dvec2 lo(params.worldOrigin);
    const double border = lo.x + kTile;
    uint64_t west = 0, east = 0, interior = 0, outside = 0;
    for (uint32_t tx = 0; tx < 2; ++tx) {
        const RasterWindow where = landCoverTileWindow(grid, {tx, 0}, 15.0);
        const GrassMap map = makeLandCoverWindowGrassMap(cut(raster, where), where, grid.rasterSize, {tx * 5, 0, 5, 5},
                                                         worldCover(15.0), grid.pixelSize, "test");
        const glm::vec2 origin = params.worldOrigin + glm::vec2(float(kTile) * float(tx), 0.0f);
        const Ground flat(Heightfield(2, 2, float(kTile), origin, {0, 0, 0, 0}));
        const VegetationTile tile = generateTile(flat, map, params, TileCoord{int32_t(tx), 0}, 2);
        for (const FieldVegetation& field : tile.fields)
            for (const gpu::PlantStatic& r : field.staticRecords) {
                if (decodePlantStatic(r).category != 1) continue; // grass
                const glm::dvec3 p(decodePlantPosition(r, field.origin, field.positionStep));
                if (p.y < lo.y + kStrip || p.y > lo.y + kTile - kStrip) continue; // away from the world's own edges
                const double d = p.x - border;                                    // east of the border
                if (p.x < lo.x || p.x >= lo.x + 2.0 * kTile)
                    ++outside;
                else if (d >= -kStrip && d < 0.0)
                    ++west;
                else if (d >= 0.0 && d < kStrip)
                    ++east;
                else if (std::abs(d) >= 4.0 * kStrip && std::abs(d) < kTile - kStrip)
                    ++interior;
            }
    }
    const double stripArea = kStrip * (kTile - 2.0 * kStrip);
    const double interiorArea = 2.0 * (kTile - 5.0 * kStrip) * (kTile - 2.0 * kStrip);
    const double interiorDensity = double(interior) / interiorArea;
    EXPECT_NEAR(interiorDensity, 16.0, 16.0 * 0.05); // grassland: intensity 1 of 16 grass plants per m^2
    EXPECT_EQ(outside, 0u);
    EXPECT_NEAR(double(west) / stripArea / interiorDensity, 1.0, 0.2) << west;
    EXPECT_NEAR(double(east) / stripArea / interiorDensity, 1.0, 0.2) << east;
    std::printf("[ figures  ] interior %.3f grass plants/m^2; border strips west %.3f, east %.3f of it\n",
                interiorDensity, double(west) / stripArea / interiorDensity,
                double(east) / stripArea / interiorDensity);
}
