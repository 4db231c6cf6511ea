// Acceptance tests of issue 6, CPU side: colliders, the collision pass, field activity, the CPU reference of the
// recovery (simulateOnCpu) and save / restore. Everything runs without a GPU.
#include "test_files.h"
#include "interaction_world.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

using namespace sward;
using namespace sward::test;


TEST(Interaction, UntouchedFieldsNeverActiveAndTouchedOnesSleepAfterRestTicks) {
    const VegetationTile& tile = smallTile();
    InteractionParams params;
    params.recovery.restTicks = 40;
    Sim sim = makeSim(tile, params);
    // Field 0 is x, y in [0, 25): the sphere stays inside it for 10 ticks.
    uint64_t lastContact = 0;
    for (uint32_t t = 0; t < 10; ++t) {
        Collider s = sphereAt(t);
        TickResult r = sim.step(std::span(&s, 1));
        ASSERT_EQ(r.touchedFields, std::vector<uint32_t>{0});
        EXPECT_EQ(r.activeFields, std::vector<uint32_t>{0});
        EXPECT_EQ(sim.world.lastContactTick(0), r.tick);
        lastContact = r.tick;
    }
    for (uint32_t t = 0; t < 60; ++t) {
        TickResult r = sim.step({});
        EXPECT_TRUE(r.contacts.empty());
        bool shouldBeActive = r.tick - lastContact < params.recovery.restTicks;
        EXPECT_EQ(r.activeFields, shouldBeActive ? std::vector<uint32_t>{0} : std::vector<uint32_t>{}) << r.tick;
    }
    for (uint32_t f = 1; f < tile.fields.size(); ++f) EXPECT_FALSE(sim.world.fieldActive(f));
    // Recovered within the configured time: nothing moves any more.
    for (const auto& d : sim.dynamics) EXPECT_TRUE(plantSettled(d));
}

// One world per thread count, plus one whose pool is resized between ticks: every tick's contacts, fields and
// statistics, and the simulated records, must be bitwise the same.
TEST(Interaction, ParamsParseWithDefaultsAndRejectUnknownKeys) {
    InteractionParams p =
        parseInteractionParams(nlohmann::json::parse(R"({"categories": [{"fell_force": 2.5}, {"push_gain": 3}],
                                  "recovery": {"rest_ticks": 12, "stiffness": 20}})"),
                               "scene.json");
    EXPECT_EQ(p.categories[0].fellForce, 2.5f);
    EXPECT_EQ(p.categories[0].pushGain, 2.0f);
    EXPECT_EQ(p.categories[1].pushGain, 3.0f);
    EXPECT_EQ(p.categories[1].fellForce, 0.6f);
    EXPECT_EQ(p.categories[2].fellForce, 0.8f);
    EXPECT_EQ(p.recovery.restTicks, 12u);
    EXPECT_EQ(p.recovery.stiffness, 20.0f);
    EXPECT_EQ(p.recovery.damping, RecoveryParams{}.damping);
    for (const char* bad :
         {R"({"colour": 1})", R"({"categories": [{"fel_force": 1}]})", R"({"recovery": {"rest_ticks": -1}})",
          R"({"recovery": {"fell_bend": 2}})", R"({"categories": [{}, {}, {}, {}, {}]})"}) {
        try {
            parseInteractionParams(nlohmann::json::parse(bad), "scene.json");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos);
        }
    }
}

// The issue's worst case: one colliding sphere on every 5 x 5 m cluster of a full 500 x 500 m tile at 16 plants/m^2
// (400 fields x 25 colliders). Prints the collision time; the goal is <= 4 ms on 2 cores.
