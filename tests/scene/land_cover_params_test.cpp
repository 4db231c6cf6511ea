// The scene's "land_cover" key: the preset, the table, the border, band and nodata, the errors naming the key, and
// the grass map a scene builds from it.
#include "scene/land_cover_params.h"
#include "scene/scene.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace sward;
using namespace sward::test;

namespace {

LandCoverParams parse(const char* json) {
    const nlohmann::json value = nlohmann::json::parse(json);
    JsonReader r(value, "s.json", "land_cover");
    LandCoverParams params = parseLandCoverParams(r);
    r.finish();
    return params;
}

std::string parseError(const char* json) {
    return errorOf([&] { parse(json); });
}

std::string sceneError(const char* json) {
    return errorOf([&] { parseScene(nlohmann::json::parse(json), "s.json"); });
}

} // namespace

TEST(LandCoverParams, PresetWithDefaults) {
    const LandCoverParams p = parse(R"({"preset": "esa_worldcover"})");
    EXPECT_EQ(p.table.classes, esaWorldCoverTable().classes);
    EXPECT_EQ(p.table.channels, 3u);
    EXPECT_EQ(p.borderWidth, 5.0);
    EXPECT_EQ(p.band, 1u);
    EXPECT_FALSE(p.nodataCode);
}

TEST(LandCoverParams, TableEntriesOverrideAndExtendThePreset) {
    const LandCoverParams p = parse(R"({"preset": "esa_worldcover", "table": {"30": [0, 0.5, 0.25],
                                         "200": [1, 0, 0, 0.5]}, "border": 12.5, "band": 2, "nodata": 200})");
    EXPECT_EQ(*p.table.find(30), glm::vec4(0.0f, 0.5f, 0.25f, 0.0f));
    EXPECT_EQ(*p.table.find(200), glm::vec4(1.0f, 0.0f, 0.0f, 0.5f));
    EXPECT_EQ(*p.table.find(10), *esaWorldCoverTable().find(10));
    EXPECT_EQ(p.table.classes.size(), 12u);
    EXPECT_EQ(p.table.channels, 4u); // a class feeds A
    EXPECT_EQ(p.borderWidth, 12.5);
    EXPECT_EQ(p.band, 2u);
    EXPECT_EQ(p.nodataCode, 200);
}

TEST(LandCoverParams, ATableAloneIsEnough) {
    const LandCoverParams p = parse(R"({"table": {"0": [0, 0, 0], "4294967295": [0, 1, 0]}, "border": 0})");
    EXPECT_EQ(p.table.classes.size(), 2u);
    EXPECT_EQ(p.table.find(4294967295)->g, 1.0f);
    EXPECT_EQ(p.borderWidth, 0.0);
}

TEST(LandCoverParams, BadValuesNameTheKey) {
    EXPECT_NE(parseError(R"({})").find("s.json: 'land_cover' needs a 'preset' or a 'table'"), std::string::npos);
    EXPECT_NE(parseError(R"({"preset": "corine"})").find("'land_cover.preset' must be esa_worldcover"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"table": {"grass": [0, 1, 0]}})")
                  .find("s.json: 'land_cover.table' class code must be a whole number from 0 to 4294967295, got "
                        "'grass'"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"table": {"-1": [0, 1, 0]}})").find("'land_cover.table' class code"), std::string::npos);
    EXPECT_NE(parseError(R"({"table": {"10": [0, 1, 0], "010": [1, 0, 0]}})")
                  .find("names class code 10 twice ('010' and '10')"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"table": {"10": [0, 1]}})").find("'land_cover.table.10' must be an array of 3 or 4"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"table": {"10": [0, 1, 101]}})").find("'land_cover.table.10' must hold numbers"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"table": [1, 2]})").find("land_cover.table"), std::string::npos);
    EXPECT_NE(parseError(R"({"preset": "esa_worldcover", "border": 1001})").find("'land_cover.border'"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"preset": "esa_worldcover", "band": 0})").find("'land_cover.band'"), std::string::npos);
    EXPECT_NE(parseError(R"({"preset": "esa_worldcover", "nodata": 0})")
                  .find("'land_cover.nodata' is class code 0, which the table lacks"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"preset": "esa_worldcover", "bordr": 3})").find("bordr"), std::string::npos);
}

TEST(LandCoverScene, FileIsRequiredAndGrassMapExcludesIt) {
    EXPECT_NE(sceneError(R"({"land_cover": {"preset": "esa_worldcover"}})").find("'land_cover.file' is required"),
              std::string::npos);
    EXPECT_NE(sceneError(R"({"grass_map": "m.png", "land_cover": {"file": "c.tif", "preset": "esa_worldcover"}})")
                  .find("s.json: 'grass_map' and 'land_cover' both give the grass map"),
              std::string::npos);
}

TEST(LandCoverScene, BuildsTheGrassMapFromTheRasterOverTheTile) {
    SWARD_SKIP_WITHOUT(Gdal); // a land-cover raster
    const auto dir = tempDir();
    writePng(dir / "cover.png", 2, 1, 1, 8, {30.0f / 255.0f, 80.0f / 255.0f});
    std::ofstream(dir / "s.json") << R"({"terrain": {"size": 100}, "land_cover": {"file": "cover.png",
        "preset": "esa_worldcover", "table": {"80": [0, 0, 0.5]}, "border": 20}})";
    const Scene scene = loadScene((dir / "s.json").string());
    EXPECT_EQ(scene.landCover.file, (dir / "cover.png").string());
    EXPECT_TRUE(scene.grassMapPath.empty());
    const GrassMap map = buildGrassMap(scene, scene.vegetation.tileSize);
    ASSERT_EQ(map.width(), 2u);
    // 50 m pixels, a 20 m border: each pixel's box reaches 10 m past its centre, not into the other pixel.
    EXPECT_EQ(map.values(), (std::vector<float>{0.05f, 1.0f, 0.3f, 0.0f, 0.0f, 0.5f}));
}

TEST(LandCoverScene, CodeMissingFromTheTableNamesTheSceneKey) {
    SWARD_SKIP_WITHOUT(Gdal); // a land-cover raster
    const auto dir = tempDir();
    writePng(dir / "cover.png", 2, 1, 1, 8, {30.0f / 255.0f, 7.0f / 255.0f});
    std::ofstream(dir / "s.json") << R"({"land_cover": {"file": "cover.png", "preset": "esa_worldcover"}})";
    const Scene scene = loadScene((dir / "s.json").string());
    expectError([&] { buildGrassMap(scene, scene.vegetation.tileSize); },
                {(dir / "s.json").string() + ": 'land_cover': class code 7 of raster '" + (dir / "cover.png").string() +
                 "' (first at pixel (1, 0))"});
}
