// The scene file's "interaction" object, read through the one JSON reader.
#include "common/error.h"
#include "interaction/interaction_params.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <string>

using namespace sward;

namespace {
std::string errorOf(const char* json) {
    try {
        parseInteractionParams(nlohmann::json::parse(json), "scene.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
} // namespace

TEST(Interaction, ParamsParseWithDefaultsAndRejectUnknownKeys) {
    InteractionParams p =
        parseInteractionParams(nlohmann::json::parse(R"({"categories": [{"fell_force": 2.5}, {"push_gain": 3, "max_bend": 0.7}],
                                  "recovery": {"rest_ticks": 12, "stiffness": 20}})"),
                               "scene.json");
    EXPECT_EQ(p.categories[0].fellForce, 2.5f);
    EXPECT_EQ(p.categories[0].pushGain, 2.0f);
    EXPECT_EQ(p.categories[1].pushGain, 3.0f);
    EXPECT_EQ(p.categories[1].fellForce, 0.6f);
    EXPECT_EQ(p.categories[2].fellForce, 0.8f);
    EXPECT_EQ(p.categories[1].maxBend, 0.7f);
    EXPECT_EQ(p.categories[0].maxBend, INFINITY) << "no bend limit unless the scene sets one";
    EXPECT_EQ(p.recovery.restTicks, 12u);
    EXPECT_EQ(p.recovery.stiffness, 20.0f);
    EXPECT_EQ(p.recovery.damping, RecoveryParams{}.damping);
    for (const char* bad :
         {R"({"colour": 1})", R"({"categories": [{"fel_force": 1}]})", R"({"recovery": {"rest_ticks": -1}})",
          R"({"recovery": {"fell_bend": 2}})", R"({"categories": [{}, {}, {}, {}, {}]})",
          R"({"categories": [{"max_bend": 0}]})"}) {
        try {
            parseInteractionParams(nlohmann::json::parse(bad), "scene.json");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos);
        }
    }
}

TEST(Interaction, ParamsErrorsNameTheJsonPathInTheReadersWording) {
    EXPECT_EQ(errorOf(R"({"colour": 1})"), "scene.json: unknown key 'interaction.colour'");
    EXPECT_EQ(errorOf(R"({"categories": [{"fel_force": 1}]})"),
              "scene.json: unknown key 'interaction.categories[0].fel_force'");
    EXPECT_EQ(errorOf(R"({"categories": [{}, {"push_gain": 2000}]})"),
              "scene.json: 'interaction.categories[1].push_gain' must be between 0 and 1000 (got 2000)");
    EXPECT_EQ(errorOf(R"({"categories": [{}, {}, {}, {}, {}]})"),
              "scene.json: 'interaction.categories' must be an array of 1 to 4 objects");
    EXPECT_EQ(errorOf(R"({"categories": []})"),
              "scene.json: 'interaction.categories' must be an array of 1 to 4 objects");
    EXPECT_EQ(errorOf(R"({"recovery": {"rest_ticks": -1}})"),
              "scene.json: 'interaction.recovery.rest_ticks' must be an integer in [1, 1000000] (got -1)");
    EXPECT_EQ(errorOf(R"({"recovery": {"fell_bend": 2}})"),
              "scene.json: 'interaction.recovery.fell_bend' must be between 0 and 0.95 (got 2)");
    EXPECT_EQ(errorOf(R"({"recovery": 3})"), "scene.json: 'interaction.recovery' must be an object");
    EXPECT_EQ(errorOf("[]"), "scene.json: 'interaction' must be an object");
}
