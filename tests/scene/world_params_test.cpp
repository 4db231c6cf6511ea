// The scene's "world" key: parsing, its requirements on the rest of the scene, and the memory bound checked before
// any tile is generated.
#include "scene/scene.h"
#include "scene/world_params.h"

#include "test_files.h"

#include <gtest/gtest.h>

using namespace sward;
using namespace sward::test;

namespace {

nlohmann::json worldJson() {
    return {{"terrain", {{"size", 500}}}, {"world", {{"tiles", {16, 16}}, {"load_radius", 300}}}};
}

std::string parseError(const nlohmann::json& json) {
    return errorOf([&] { parseScene(json, "w.json"); });
}

} // namespace

TEST(WorldParams, KeysAndDefaults) {
    const Scene plain = parseScene(nlohmann::json::object(), "w.json");
    EXPECT_FALSE(plain.world.enabled);
    const Scene scene = parseScene(worldJson(), "w.json");
    EXPECT_TRUE(scene.world.enabled);
    EXPECT_EQ(scene.world.tilesX, 16u);
    EXPECT_EQ(scene.world.loadRadius, 300.0);
    EXPECT_EQ(scene.world.evictRadius, 400.0); // load_radius + 100
    EXPECT_EQ(scene.world.memoryBudgetBytes, uint64_t(2048) << 20);
}

TEST(WorldParams, TheMostTilesADiscTouches) {
    // 300 m on 500 m tiles: on an edge's midpoint, two columns of three rows.
    EXPECT_EQ(maxTilesWithin(300.0, 500.0, 16, 16), 6u);
    // 400 m from a tile's centre reaches its eight neighbours.
    EXPECT_EQ(maxTilesWithin(400.0, 500.0, 16, 16), 9u);
    EXPECT_EQ(maxTilesWithin(100.0, 500.0, 16, 16), 4u); // a corner
    EXPECT_EQ(maxTilesWithin(5000.0, 500.0, 4, 3), 12u); // never more than the world
}

TEST(WorldParams, BadWorldsAreErrorsNamingTheKey) {
    auto with = [](const nlohmann::json& patch) {
        nlohmann::json json = worldJson();
        json.merge_patch(patch);
        return json;
    };
    EXPECT_NE(parseError(with({{"world", {{"evict_radius", 200}}}}))
                  .find("'world.evict_radius' (200 m) must be larger "
                        "than 'world.load_radius' (300 m)"),
              std::string::npos);
    EXPECT_NE(parseError(with({{"world", {{"tiles", {0, 4}}}}})).find("'world.tiles'"), std::string::npos);
    EXPECT_NE(parseError(with({{"world", {{"tiles", {80, 4}}}}})).find("'world.tiles' times 'vegetation.tile_size'"),
              std::string::npos);
    EXPECT_NE(parseError(with({{"world", {{"radius", 4}}}})).find("unknown key 'world.radius'"), std::string::npos);
    EXPECT_NE(parseError(with({{"terrain",
                                {{"size", nullptr}, {"heightmap", {{"file", "dem.png"}, {"metres_per_pixel", 1}}}}}}))
                  .find("a world reads its DEM window by window through GDAL"),
              std::string::npos);
    EXPECT_NE(parseError(with({{"grass_map", "map.png"}})).find("'grass_map'"), std::string::npos);
    EXPECT_NE(parseError(with({{"vegetation", {{"tile_size", 250}}}}))
                  .find("'vegetation.tile_size' (250 m) must equal "
                        "'terrain.size' (500 m)"),
              std::string::npos);
    EXPECT_NE(parseError(with({{"terrain", {{"size", 125}, {"spacing", 2}}}})).find("'terrain.spacing'"),
              std::string::npos);
    EXPECT_NE(parseError(with({{"vegetation", {{"world_origin", {1, 0}}}}})).find("'vegetation.world_origin'"),
              std::string::npos);
}

TEST(WorldParams, ABudgetTooSmallForTheTilesAroundOneCameraIsRefusedUpFront) {
    nlohmann::json json = worldJson();
    json["world"]["memory_budget_mib"] = 500;
    const std::string error = parseError(json);
    EXPECT_NE(error.find("w.json: 'world.memory_budget_mib' (500 MiB) cannot hold the tiles around one camera: up to 9 "
                         "tiles"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("'world.load_radius'"), std::string::npos);
    EXPECT_NE(error.find("each up to 108 MiB"), std::string::npos) << error; // docs/scene-format.md quotes it
    // A lower density fits.
    json["vegetation"]["density_multiplier"] = 0.25;
    EXPECT_NO_THROW(parseScene(json, "w.json"));
}

TEST(WorldParams, ABudgetAboveThePhysicalMemoryIsRefusedNeverLowered) {
    ASSERT_GT(physicalMemoryBytes(), uint64_t(1) << 26);
    // 1 TiB, the budget that grew 50 MB/s with no frame (a machine of more than 1 TiB would accept it).
    if (physicalMemoryBytes() < (uint64_t(1) << 40)) {
        nlohmann::json json = worldJson();
        json["world"]["memory_budget_mib"] = 1048576;
        const std::string error = parseError(json);
        EXPECT_NE(error.find("w.json: 'world.memory_budget_mib' (1048576 MiB) is more than this machine's memory ("),
                  std::string::npos)
            << error;
    }
    nlohmann::json small = worldJson();
    small["world"]["memory_budget_mib"] = 3000;
    EXPECT_EQ(parseScene(small, "w.json").world.memoryBudgetBytes, uint64_t(3000) << 20) << "kept as written";
}
