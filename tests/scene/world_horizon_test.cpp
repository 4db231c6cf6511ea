// The horizon ring's heights (scene/world_horizon.h) and the world's "horizon" key (scene/world_params.h).
#include "common/error.h"
#include "scene/scene.h"
#include "scene/world_horizon.h"
#include "world/heightfield.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace sward;

namespace {

// 3 x 2 tiles of 30 m on a lattice of 0.6 m (not a binary fraction), the world's origin off zero.
nlohmann::json horizonWorld() {
    return nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 30, "spacing": 0.6, "amplitude": 6, "feature_size": 30, "octaves": 4},
        "vegetation": {"tile_size": 30, "field_size": 15, "world_origin": [-30, 15]},
        "world": {"tiles": [3, 2], "view_distance": 20, "memory_budget_mib": 256, "horizon": {"spacing": 1.8}}
    })");
}

std::string parseError(const nlohmann::json& json) {
    try {
        parseScene(json, "horizon.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

// Every ring sample is bitwise the tiles' height at the same lattice vertex: tile (x, y)'s terrain, made as
// generateWorldTile makes it, sampled at every third vertex from the world's origin.
TEST(WorldHorizon, RingHeightsAreTheTilesLatticeSamplesBitwise) {
    const Scene scene = parseScene(horizonWorld(), "horizon.json");
    const Heightfield ring = horizonHeights(scene);
    ASSERT_EQ(ring.columns(), 51u); // 90 m / 1.8 m + 1
    ASSERT_EQ(ring.rows(), 35u);    // 60 m / 1.8 m + 1 (33.3 cells, rounded up)
    EXPECT_FLOAT_EQ(ring.spacing(), 1.8f);
    uint32_t compared = 0;
    for (int ty = 0; ty < 2; ++ty)
        for (int tx = 0; tx < 3; ++tx) {
            ProceduralTerrainParams t = scene.terrain.procedural;
            t.origin = glm::dvec2(-30.0 + 30.0 * tx, 15.0 + 30.0 * ty);
            const Heightfield fine = makeProceduralTerrain(t);
            for (uint32_t j = 0; j < fine.rows(); ++j)
                for (uint32_t i = 0; i < fine.columns(); ++i) {
                    const uint32_t gi = 50 * tx + i, gj = 50 * ty + j; // world lattice index from the origin
                    if (gi % 3 || gj % 3) continue;
                    ASSERT_EQ(ring.sample(gi / 3, gj / 3), fine.sample(i, j)) << "tile " << tx << "," << ty;
                    ++compared;
                }
        }
    EXPECT_EQ(compared, 51u * 34u); // every ring sample inside the world (the last row lies beyond it)
}

TEST(WorldHorizon, OnByDefaultOffWithFalseAndSpacingChecked) {
    nlohmann::json json = horizonWorld();
    json["world"].erase("horizon");
    Scene scene = parseScene(json, "horizon.json");
    EXPECT_TRUE(scene.world.horizon);
    EXPECT_NEAR(horizonSpacing(scene), 0.6, 1e-6); // 90 m / 0.6 m = 150 cells: the default's 256 allow the lattice
    json["world"]["tiles"] = {256, 1};
    EXPECT_NEAR(horizonSpacing(parseScene(json, "horizon.json")), 30.0, 1e-5); // 7680 m: 12,800 cells -> 256
    json = horizonWorld();
    json["world"]["horizon"] = false;
    EXPECT_FALSE(parseScene(json, "horizon.json").world.horizon);
    json["world"]["horizon"] = {{"spacing", 1.0}};
    EXPECT_NE(parseError(json).find("'world.horizon.spacing' (1 m) must be a whole multiple of 'terrain.spacing'"),
              std::string::npos)
        << parseError(json);
    json["world"]["horizon"] = {{"spacing", -3}};
    EXPECT_NE(parseError(json).find("'world.horizon.spacing'"), std::string::npos) << parseError(json);
    json["world"]["horizon"] = {{"spacng", 3}};
    EXPECT_NE(parseError(json).find("spacng"), std::string::npos) << parseError(json);
    json["world"]["horizon"] = 5;
    EXPECT_NE(parseError(json).find("'world.horizon' must be false, true or an object"), std::string::npos)
        << parseError(json);
}
