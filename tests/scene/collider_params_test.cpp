// Colliders a program places at each tick (the Python module's set_colliders): the scene's shape keys plus a centre.
#include "scene/collider_params.h"

#include "common/error.h"
#include "common/json_reader.h"

#include <gtest/gtest.h>

using namespace sward;

TEST(PlacedColliders, ShapesSitAtTheirCentreWithIdsApartFromTheScenes) {
    const auto colliders = parsePlacedColliders(parseJsonText(R"([
        {"centre": [1, 2, 3], "radius": 0.25, "force": 4},
        {"centre": [5, 6, 7], "shape": "capsule", "length": 2},
        {"centre": [0, 0, 1], "shape": "box", "half_extents": [0.5, 1, 2], "kind": "mower", "cut_height": 0.2}
    ])", "test", "colliders"), "colliders");
    ASSERT_EQ(colliders.size(), 3u);
    EXPECT_EQ(colliders[0].id, kPlacedColliderBase);
    EXPECT_EQ(colliders[2].id, kPlacedColliderBase + 2);
    EXPECT_EQ(colliders[0].centre, glm::vec3(1, 2, 3));
    EXPECT_EQ(colliders[0].radius, 0.25f);
    EXPECT_EQ(colliders[0].force, 4.0f);
    EXPECT_EQ(colliders[1].centre, glm::vec3(4, 6, 7)); // a capsule's segment runs along x from its centre
    EXPECT_EQ(colliders[1].end, glm::vec3(6, 6, 7));
    EXPECT_EQ(colliders[2].kind, ColliderKind::Mower);
    EXPECT_EQ(colliders[2].halfExtents, glm::vec3(0.5f, 1.0f, 2.0f));
}

TEST(PlacedColliders, BadCollidersAreOneErrorNamingTheElement) {
    auto error = [](const char* text) {
        try {
            parsePlacedColliders(parseJsonText(text, "test", "colliders"), "colliders");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error(R"([{"radius": 1}])").find("'[0].centre' is required"), std::string::npos);
    EXPECT_NE(error(R"([{"centre": [0, 0, 0]}, {"centre": [0, 0, 0], "radius": -1}])").find("'[1].radius'"),
              std::string::npos);
    EXPECT_NE(error(R"([{"centre": [0, 0, 0], "colour": 1}])").find("colour"), std::string::npos);
    EXPECT_EQ(error(R"({"centre": [0, 0, 0]})"), "colliders: must be an array of colliders");
}
