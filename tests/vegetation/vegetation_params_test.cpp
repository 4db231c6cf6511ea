#include "vegetation/vegetation_params.h"

#include "test_files.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

using namespace sward;
using sward::test::expectError;
using Json = nlohmann::json;

TEST(VegetationParams, EmptyObjectGivesDocumentedDefaults) {
    const VegetationParams p = parseVegetationParams(Json::object(), "scene.json");
    EXPECT_EQ(p.tileSize, 500.0f);
    EXPECT_EQ(p.fieldsPerTile(), 20u);
    EXPECT_EQ(p.clustersPerField(), 5u);
    EXPECT_EQ(p.categoryCount, 3u);
    EXPECT_EQ(p.categories[1].name, "grass");
    EXPECT_EQ(p.channelCategory[0], 0);
    EXPECT_EQ(p.channelCategory[3], kUnusedChannel);
}

TEST(VegetationParams, ParsesEveryKey) {
    const Json j = Json::parse(R"({
        "seed": 42, "tile_size": 200, "field_size": 20, "cluster_size": 4, "world_origin": [-100, 50],
        "density_multiplier": 0.5, "up_normal_blend": 1, "memory_budget_mib": 64,
        "categories": [{"name": "moss", "density": 3, "height": 0.1, "height_variation": 0.2, "variants": 2},
                       {"name": "reeds"}],
        "channels": {"r": null, "g": "reeds", "b": 0}
    })");
    const VegetationParams p = parseVegetationParams(j, "scene.json");
    EXPECT_EQ(p.seed, 42u);
    EXPECT_EQ(p.fieldsPerTile(), 10u);
    EXPECT_EQ(p.clustersPerField(), 5u);
    EXPECT_EQ(p.worldOrigin, glm::vec2(-100.0f, 50.0f));
    EXPECT_EQ(p.memoryBudgetBytes, uint64_t(64) << 20);
    EXPECT_EQ(p.categoryCount, 2u);
    EXPECT_EQ(p.categories[0].variants, 2u);
    EXPECT_EQ(p.categories[1].density, defaultVegetationCategory(1).density); // defaults per index
    EXPECT_EQ(p.channelCategory, (std::array<int32_t, 4>{kUnusedChannel, 1, 0, kUnusedChannel}));
}

TEST(VegetationParams, RejectsNegativeDensityNamingSourceAndKey) {
    expectError([] { parseVegetationParams(Json::parse(R"({"categories": [{"density": -1}]})"), "meadow.json"); },
                {"meadow.json", "categories[0].density", "-1"});
}

TEST(VegetationParams, RejectsNonNumbersUnknownKeysAndBadNesting) {
    expectError([] { parseVegetationParams(Json::parse(R"({"up_normal_blend": "x"})"), "s.json"); },
                {"s.json", "up_normal_blend", "number"});
    expectError([] { parseVegetationParams(Json::parse(R"({"densty_multiplier": 2})"), "s.json"); },
                {"unknown key 'vegetation.densty_multiplier'"});
    expectError([] { parseVegetationParams(Json::parse(R"({"field_size": 24})"), "s.json"); },
                {"tile_size", "whole multiple"});
    expectError([] { parseVegetationParams(Json::parse(R"({"channels": {"a": 3}})"), "s.json"); },
                {"channels.a", "category 3"});
    expectError([] { parseVegetationParams(Json::parse(R"({"categories": [{"height": 1e40}]})"), "s.json"); },
                {"categories[0].height", "got 1e+40"});
}
