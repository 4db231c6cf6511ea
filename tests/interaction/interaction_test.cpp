// Acceptance test of issue 6, CPU side: field activity of the interaction world with the CPU reference of the
// recovery (simulateOnCpu). Runs without a GPU.
#include "interaction_world.h"

#include <gtest/gtest.h>

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
