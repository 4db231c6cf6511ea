// A world's land cover (issue 51, part B): each tile's grass map is the land-cover raster's window over the tile,
// bitwise the whole raster's map cut there; a raster whose georeferenced extent is not the world's is one error
// naming both; the budget's per-tile bound holds with intensities above 1; tiles are the same streamed or resident,
// on a procedural and on a DEM ground.
#include "scene/land_cover_params.h"
#include "scene/world_params.h"
#include "scene/world_tiles.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>

using namespace sward;
using namespace sward::test;

namespace {

// An ESRI ASCII grid of width x height class codes code(x, y) (top row first), 10 m pixels, with a projected
// coordinate system in metres (UTM zone 32N) when `utm`.
std::string writeGrid(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::function<int(uint32_t, uint32_t)>& code, bool utm) {
    std::ofstream grid(path);
    grid << "ncols " << width << "\nnrows " << height << "\nxllcorner 500000\nyllcorner 4100000\ncellsize 10\n";
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) grid << code(x, y) << (x + 1 == width ? "\n" : " ");
    if (utm)
        std::ofstream(std::filesystem::path(path).replace_extension(".prj"))
            << R"(PROJCS["WGS_1984_UTM_Zone_32N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",)"
            << R"(6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],)"
            << R"(PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",)"
            << R"(0.0],PARAMETER["Central_Meridian",9.0],PARAMETER["Scale_Factor",0.9996],)"
            << R"(PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]])";
    return path.string();
}

// Patches of grassland, shrubland, tree cover and water, 10 m pixels.
int patch(uint32_t x, uint32_t y) {
    const int classes[] = {30, 20, 10, 80, 30};
    return classes[(x / 3 + 2 * (y / 2) + (x * y) % 3) % 5];
}

// 3 x 2 tiles of 50 m over a land cover of 15 x 10 pixels (10 m), at a low density.
nlohmann::json worldJson(const std::string& landCover) {
    return {{"seed", 3},
            {"terrain", {{"size", 50}, {"spacing", 2}, {"amplitude", 3}}},
            {"vegetation", {{"tile_size", 50}, {"field_size", 25}, {"density_multiplier", 0.05}}},
            {"land_cover", {{"file", landCover}, {"preset", "esa_worldcover"}, {"border", 15}}},
            {"world", {{"tiles", {3, 2}}, {"load_radius", 30}, {"evict_radius", 40}}}};
}

// The maps of every tile of the scene's world equal the whole raster's map (read here with readRasterBand) cut at
// the tile, bitwise; `pixels` per tile along each side.
void expectTileMapsAreTheWholeRastersCut(const Scene& scene, const std::string& file, uint32_t pixels) {
    const RasterBand raster = readRasterBand(file);
    const RasterWindow all{.width = raster.width, .height = raster.height};
    const double tileSize = scene.vegetation.tileSize;
    const GrassMap whole = makeLandCoverWindowGrassMap(raster, all, {raster.width, raster.height}, all, scene.landCover,
                                                       glm::dvec2(tileSize / pixels), "test");
    for (uint32_t ty = 0; ty < scene.world.tilesY; ++ty)
        for (uint32_t tx = 0; tx < scene.world.tilesX; ++tx) {
            const glm::dvec2 origin = glm::dvec2(scene.vegetation.worldOrigin) + tileSize * glm::dvec2(tx, ty);
            const GrassMap map = buildGrassMap(scene, float(tileSize), origin);
            ASSERT_EQ(map.width(), pixels);
            ASSERT_EQ(map.height(), pixels);
            std::vector<float> expected;
            for (uint32_t y = 0; y < pixels; ++y) { // tile rows count north from the raster's south edge
                const size_t row = size_t(raster.height) - size_t(ty + 1) * pixels + y;
                const auto first = whole.values().begin() + ptrdiff_t((row * raster.width + size_t(tx) * pixels) * 3);
                expected.insert(expected.end(), first, first + 3 * pixels);
            }
            EXPECT_EQ(map.values(), expected) << "tile " << tx << ", " << ty;
        }
}

template <class T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameTile(const WorldTile& a, const WorldTile& b) {
    if (a.vegetation.fields.size() != b.vegetation.fields.size() || a.bytes != b.bytes) return false;
    for (size_t f = 0; f < a.vegetation.fields.size(); ++f)
        if (!sameBytes(a.vegetation.fields[f].staticRecords, b.vegetation.fields[f].staticRecords)) return false;
    return true;
}

} // namespace

TEST(WorldLandCover, EachTilesGrassMapIsTheWholeRastersMapCutAtTheTile) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    const std::string file = writeGrid(dir / "cover.asc", 15, 10, patch, true);
    const Scene scene = parseScene(worldJson("cover.asc"), (dir / "scene.json").string());
    expectTileMapsAreTheWholeRastersCut(scene, file, 5);
    // A raster of a larger area (200 x 120 m): the world is cut at its south-west corner, the box still clipped to
    // the raster's own edges.
    const std::string larger = writeGrid(dir / "larger.asc", 20, 12, patch, true);
    expectTileMapsAreTheWholeRastersCut(parseScene(worldJson("larger.asc"), (dir / "scene.json").string()), larger, 5);
}

// The horizon ring's far cover over a square of the world's longer side: each texel the class intensities of the
// land-cover pixel under its centre, zero beyond the raster.
TEST(WorldLandCover, PointMapSamplesTheClassUnderEachTexel) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(dir / "cover.asc", 15, 10, patch, true);
    const Scene scene = parseScene(worldJson("cover.asc"), (dir / "scene.json").string());
    const GrassMap map = worldLandCoverPointMap(scene, glm::dvec2(0.0), 150.0, 15);
    ASSERT_EQ(map.width(), 15u);
    ASSERT_EQ(map.height(), 15u);
    for (uint32_t r = 0; r < 15; ++r)
        for (uint32_t c = 0; c < 15; ++c) {
            const glm::vec4 expected =
                r < 5 ? glm::vec4(0.0f) : *scene.landCover.table.find(patch(c, r - 5)); // rows 0..4: y 100 .. 150 m
            for (uint32_t k = 0; k < 3; ++k)
                ASSERT_EQ(map.values()[(size_t(r) * 15 + c) * 3 + k], expected[int(k)]) << c << ", " << r;
        }
}

// A GIS world: a 61 x 41 sample DEM of 1 m (UTM) gives 3 x 2 tiles of 20 m from its south-west sample; the land
// cover of 6 x 4 pixels of 10 m covers the same 60 x 40 m. Each tile's map is the whole raster's cut at the tile,
// plants grow, and the tiles a small load radius streams equal those generated alone.
TEST(WorldLandCover, OnADemWorldTooTilesTakeTheirWindowAndStreamAlike) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(
        dir / "dem.asc", 61, 41, [](uint32_t x, uint32_t y) { return int((x * 7 + y * 3) % 11); }, true);
    std::filesystem::path demPath = dir / "dem.asc";
    { // 1 m samples: rewrite the header's cell size
        std::string text = readText(demPath);
        text.replace(text.find("cellsize 10"), 11, "cellsize 1");
        std::ofstream(demPath) << text;
    }
    const std::string file = writeGrid(dir / "cover.asc", 6, 4, patch, true);
    nlohmann::json json = worldJson("cover.asc");
    json["terrain"] = {{"heightmap", {{"file", "dem.asc"}}}};
    json["vegetation"] = {{"tile_size", 20}, {"field_size", 10}, {"density_multiplier", 0.05}};
    json["world"] = {{"load_radius", 12}, {"evict_radius", 20}};
    const Scene scene = parseScene(json, (dir / "scene.json").string());
    ASSERT_EQ(scene.world.tilesX, 3u);
    ASSERT_EQ(scene.world.tilesY, 2u);
    expectTileMapsAreTheWholeRastersCut(scene, file, 2);
    WorldTiles streamed(scene, 1);
    uint32_t checked = 0;
    uint64_t plants = 0;
    const glm::dvec2 origin(scene.vegetation.worldOrigin);
    for (double x = 2.0; x <= 58.0; x += 8.0) {
        const glm::dvec2 point = origin + glm::dvec2(x, 0.6 * x);
        streamed.waitFor({&point, 1});
        for (TileCoord coord : streamed.residentTiles()) {
            EXPECT_TRUE(sameTile(*streamed.find(coord), generateWorldTile(scene, coord, 2)))
                << "tile " << coord.x << ", " << coord.y;
            ++checked;
        }
    }
    for (const FieldVegetation& f : generateWorldTile(scene, {1, 1}, 1).vegetation.fields) plants += f.plantCount();
    EXPECT_GT(streamed.stats().evicted, 0u);
    EXPECT_GT(checked, 6u);
    EXPECT_GT(plants, 100u);
}

// On a georeferenced DEM the land cover lies where its own georeferencing puts it, as in any GIS: a raster of a larger
// area, reaching 20 m further west and south, gives every tile the same map as the raster cut at the world's corner
// (borders off, so the boxes do not reach the extra pixels). The DEM's samples are its pixels' centres, 0.5 m off the
// land cover's grid: the world's corner takes the nearest pixel corner. A world_origin moved 10 m east and north
// moves the land cover with it: the map of tile (0, 0) is then the map 1 pixel further in.
TEST(WorldLandCover, OnAGeoreferencedDemTheLandCoverLiesWhereItsGeoreferencingPutsIt) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(
        dir / "dem.asc", 61, 41, [](uint32_t x, uint32_t y) { return int((x * 7 + y * 3) % 11); }, true);
    {
        std::string text = readText(dir / "dem.asc");
        text.replace(text.find("cellsize 10"), 11, "cellsize 1");
        std::ofstream(dir / "dem.asc") << text;
    }
    writeGrid(dir / "cover.asc", 6, 4, patch, true);
    writeGrid(
        dir / "larger.asc", 8, 6, [](uint32_t x, uint32_t y) { return x >= 2 && y < 4 ? patch(x - 2, y) : 80; }, true);
    { // the larger raster's corner 20 m west and south
        std::string text = readText(dir / "larger.asc");
        text.replace(text.find("xllcorner 500000"), 16, "xllcorner 499980");
        text.replace(text.find("yllcorner 4100000"), 17, "yllcorner 4099980");
        std::ofstream(dir / "larger.asc") << text;
    }
    auto scene = [&](const std::string& cover, double shift) {
        nlohmann::json json = worldJson(cover);
        json["terrain"] = {{"heightmap", {{"file", "dem.asc"}}}};
        json["land_cover"]["border"] = 0;
        json["vegetation"] = {{"tile_size", 20}, {"field_size", 10}, {"density_multiplier", 0.05}};
        json["world"] = {{"load_radius", 12}, {"evict_radius", 20}};
        if (shift > 0.0) json["vegetation"]["world_origin"] = {shift, shift}, json["world"]["tiles"] = {2, 1};
        return parseScene(json, (dir / "scene.json").string());
    };
    const Scene exact = scene("cover.asc", 0.0), larger = scene("larger.asc", 0.0);
    for (uint32_t ty = 0; ty < 2; ++ty)
        for (uint32_t tx = 0; tx < 3; ++tx) {
            const glm::dvec2 origin = glm::dvec2(exact.vegetation.worldOrigin) + 20.0 * glm::dvec2(tx, ty);
            EXPECT_EQ(buildGrassMap(larger, 20.0f, origin).values(), buildGrassMap(exact, 20.0f, origin).values())
                << "tile " << tx << ", " << ty;
        }
    const Scene moved = scene("larger.asc", 10.0);
    const GrassMap inner = buildGrassMap(moved, 20.0f, glm::dvec2(moved.vegetation.worldOrigin));
    const GrassMap whole = buildGrassMap(exact, 20.0f, glm::dvec2(exact.vegetation.worldOrigin));
    // Tile (0, 0) of the moved world: pixels 1..2 east and north of the exact world's corner; the exact world's tile
    // (0, 0) holds pixels 0..1, so the moved tile's south-west pixel is the exact tile's north-east one.
    ASSERT_EQ(inner.width(), 2u);
    for (uint32_t k = 0; k < 3; ++k) EXPECT_EQ(inner.values()[2 * 3 + k], whole.values()[1 * 3 + k]) << k;
}

TEST(WorldLandCover, MismatchedExtentIsOneErrorNamingBothExtents) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(dir / "cover.asc", 14, 10, patch, true); // 140 m across a 150 m world
    expectError([&] { parseScene(worldJson("cover.asc"), (dir / "scene.json").string()); },
                {"scene.json: 'land_cover': raster '", "cover.asc' covers 140 x 100 m (14 x 10 pixels of 10 x 10 m), "
                                                       "but the world covers 150 x 100 m (3 x 2 tiles of 50 m)"});
    writeGrid(dir / "plain.asc", 16, 10, patch, false); // no coordinate system: stretched, but 16 pixels over 3 tiles
    expectError([&] { parseScene(worldJson("plain.asc"), (dir / "scene.json").string()); },
                {"plain.asc' has 16 x 10 pixels, not a whole number of pixels per tile"});
}

// A grass_map in a world: the image stretched over the world's tiles, each tile's map its pixels; the budget bounds a
// tile by the image's largest values; an image without whole pixels per tile is refused naming both counts.
TEST(WorldLandCover, AGrassMapIsCutIntoTheWorldsTiles) {
    const auto dir = tempDir();
    std::vector<float> values;
    for (uint32_t i = 0; i < 15 * 10; ++i)
        for (uint32_t c = 0; c < 3; ++c) values.push_back(float((i * 7 + c * 3) % 16) / 15.0f);
    writePng(dir / "map.png", 15, 10, 3, 8, values);
    nlohmann::json json = worldJson("unused");
    json.erase("land_cover");
    json["grass_map"] = "map.png";
    const Scene scene = parseScene(json, (dir / "scene.json").string());
    const GrassMap whole = loadGrassMap((dir / "map.png").string());
    for (int32_t ty = 0; ty < 2; ++ty)
        for (int32_t tx = 0; tx < 3; ++tx) {
            const GrassMap map = buildGrassMap(scene, 50.0f, glm::dvec2(50.0 * tx, 50.0 * ty));
            ASSERT_EQ(map.width(), 5u);
            ASSERT_EQ(map.height(), 5u);
            std::vector<float> expected;
            for (uint32_t y = 0; y < 5; ++y) {
                const auto first = whole.values().begin() + ptrdiff_t(((size_t(1 - ty) * 5 + y) * 15 + tx * 5) * 3);
                expected.insert(expected.end(), first, first + 15);
            }
            EXPECT_EQ(map.values(), expected) << "tile " << tx << ", " << ty;
        }
    const WorldTile tile = generateWorldTile(scene, {1, 1}, 1);
    EXPECT_GT(tile.vegetation.fields.size(), 0u);
    EXPECT_LE(tile.bytes, predictedTileBytes(scene));
    writePng(dir / "odd.png", 16, 10, 3, 8, std::vector<float>(16 * 10 * 3, 0.5f));
    json["grass_map"] = "odd.png";
    expectError([&] { parseScene(json, (dir / "scene.json").string()); },
                {"scene.json: 'grass_map': raster '", "odd.png' has 16 x 10 pixels, not a whole number of pixels per "
                                                      "tile of the world's 150 x 100 m (3 x 2 tiles of 50 m)"});
}

// predictedTileBytes bounded the meadow's intensities, never over 1; a land cover's reach kMaxLandCoverIntensity.
// With grassland at 3 x the preset and density_multiplier 0.2, a tile holds more plants than the meadow bound allows.
TEST(WorldLandCover, TheBudgetsTileBoundHoldsIntensitiesOverOne) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(
        dir / "cover.asc", 15, 10, [](uint32_t, uint32_t) { return 30; }, true);
    nlohmann::json json = worldJson("cover.asc");
    json["land_cover"]["table"] = {{"30", {0.15, 3.0, 0.9}}};
    json["vegetation"]["density_multiplier"] = 0.2;
    const Scene scene = parseScene(json, (dir / "scene.json").string());
    const WorldTile tile = generateWorldTile(scene, {2, 1}, 1);
    Scene meadow = scene;
    meadow.landCover = {};
    EXPECT_GT(tile.bytes, predictedTileBytes(meadow)) << "the meadow's bound would not hold";
    EXPECT_LE(tile.bytes, predictedTileBytes(scene));
    EXPECT_GE(tile.bytes * 105, predictedTileBytes(scene) * 100) << "and it stays tight";
    // Drawn, a tile carries its far cover: one texel per land-cover pixel (5 x 5 here), made from its map.
    const std::vector<CategoryLook> looks(scene.vegetation.categoryCount, CategoryLook{glm::vec3(0.2f), 0.01});
    const WorldTile drawn = generateWorldTile(scene, {2, 1}, 1, looks);
    EXPECT_EQ(drawn.cover.width, 5u);
    EXPECT_EQ(drawn.cover.height, 5u);
    EXPECT_GT(drawn.bytes, tile.bytes);
    EXPECT_LE(drawn.bytes, predictedTileBytes(scene, true));
    std::printf("[ figures  ] tile %llu bytes, bound %llu, the meadow's bound %llu\n", (unsigned long long)tile.bytes,
                (unsigned long long)predictedTileBytes(scene), (unsigned long long)predictedTileBytes(meadow));
}

// The tiles a small load radius makes resident along a flight, evicting behind it, are bitwise those generated
// alone with everything resident.
TEST(WorldLandCover, TilesAreTheSameStreamedOrResident) {
    SWARD_SKIP_WITHOUT(Gdal);
    const auto dir = tempDir();
    writeGrid(dir / "cover.asc", 15, 10, patch, true);
    const Scene scene = parseScene(worldJson("cover.asc"), (dir / "scene.json").string());
    WorldTiles streamed(scene, 1);
    uint32_t checked = 0;
    for (double x = 5.0; x <= 145.0; x += 20.0) {
        const glm::dvec2 point(x, 0.6 * x);
        streamed.waitFor({&point, 1});
        for (TileCoord coord : streamed.residentTiles()) {
            EXPECT_TRUE(sameTile(*streamed.find(coord), generateWorldTile(scene, coord, 2)))
                << "tile " << coord.x << ", " << coord.y;
            ++checked;
        }
    }
    EXPECT_GT(streamed.stats().evicted, 0u);
    EXPECT_GT(checked, 6u);
}
