// GPU interaction update (contacts + damped spring) against its CPU reference; idle fields cost nothing.
#include "gpu_test.h"

#include "hash.h"
#include "interaction_gpu.h"
#include "records.h"
#include "scene.h"

#include <cstring>

using namespace sward;
using sward::test::GpuTest;

namespace {

VegetationTile smallTile() {
    Scene scene = parseScene(nlohmann::json::parse(R"({"seed": 3, "terrain": {"size": 50, "spacing": 2}})"), "t");
    return buildVegetation(scene, buildTerrain(scene), 2);
}

// Deterministic contacts on a few plants of the given fields: pushes, some cuts, some fells.
std::vector<gpu::PlantContact> makeContacts(const VegetationTile& tile, const std::vector<uint32_t>& fields, uint64_t tick,
                                            const RecoveryParams& params) {
    std::vector<gpu::PlantContact> contacts;
    for (uint32_t f : fields) {
        const FieldVegetation& field = tile.fields[f];
        for (uint32_t i = 0; i < field.plantCount(); i += 7) {
            uint64_t h = hashKey({tick, f, i});
            if ((h & 3u) != 0) continue;
            float angle = unitFloat(h >> 8) * 6.2831853f, strength = 0.2f + 0.7f * unitFloat(h >> 20);
            glm::vec2 push(std::cos(angle) * strength, std::sin(angle) * strength);
            uint32_t kind = (h >> 40) % 10 == 0 ? gpu::kContactFell : (h >> 40) % 10 == 1 ? gpu::kContactCut : gpu::kContactPush;
            if (kind == gpu::kContactFell) push = glm::normalize(push) * params.fellBend;
            uint32_t packed = encodePlantDynamic({.bend = push}).bend;
            contacts.push_back({field.firstPlant + i, packed, kind | (uint32_t(90 + (h >> 50) % 100) << 8), f});
        }
    }
    return contacts;
}

} // namespace

TEST_F(GpuTest, RecoveryMatchesTheCpuReference) {
    VegetationTile tile = smallTile();
    VegetationBuffers buffers(*ctx, tile);
    InteractionGpu gpuInteraction(*ctx, buffers);
    RecoveryParams params;
    std::vector<gpu::PlantDynamic> cpu(buffers.plantCount, restingPlantDynamic());
    std::vector<uint32_t> active = {0, 1, 3}; // of the 2 x 2 fields

    for (uint64_t tick = 0; tick < 60; ++tick) {
        std::vector<gpu::PlantContact> contacts =
            tick < 20 && tick % 4 == 0 ? makeContacts(tile, active, tick, params) : std::vector<gpu::PlantContact>{};
        ctx->submitter.immediate([&](VkCommandBuffer cmd) { gpuInteraction.record(cmd, contacts, active, params, uint32_t(tick)); });
        for (const gpu::PlantContact& c : contacts) cpu[c.plant] = applyContact(cpu[c.plant], c, params);
        for (uint32_t f : active)
            for (uint32_t i = 0; i < tile.fields[f].plantCount(); ++i) {
                uint32_t p = tile.fields[f].firstPlant + i;
                cpu[p] = recoverStep(cpu[p], params);
            }
        if (tick % 10 != 9) continue;
        std::vector<gpu::PlantDynamic> gpu = gpuInteraction.readDynamics();
        size_t moving = 0;
        for (size_t p = 0; p < cpu.size(); ++p) {
            PlantMotion a = decodePlantDynamic(gpu[p]), b = decodePlantDynamic(cpu[p]);
            ASSERT_NEAR(a.bend.x, b.bend.x, 1e-5f) << "plant " << p << " tick " << tick;
            ASSERT_NEAR(a.bend.y, b.bend.y, 1e-5f) << "plant " << p << " tick " << tick;
            ASSERT_NEAR(a.bendVelocity.x, b.bendVelocity.x, 1e-5f) << "plant " << p << " tick " << tick;
            ASSERT_NEAR(a.bendVelocity.y, b.bendVelocity.y, 1e-5f) << "plant " << p << " tick " << tick;
            ASSERT_EQ(a.state, b.state) << "plant " << p;
            ASSERT_EQ(gpu[p].state >> 24, cpu[p].state >> 24) << "cut byte of plant " << p;
            moving += a.bend != glm::vec2(0.0f);
        }
        if (tick == 9) {
            EXPECT_GT(moving, 100u) << "the test must exercise bent plants";
        }
    }
}

TEST_F(GpuTest, IdleFieldsAreNeverDispatched) {
    VegetationTile tile = smallTile();
    VegetationBuffers buffers(*ctx, tile);
    InteractionGpu gpuInteraction(*ctx, buffers);
    RecoveryParams params;
    std::vector<gpu::PlantDynamic> before = gpuInteraction.readDynamics();
    for (uint32_t tick = 0; tick < 10; ++tick)
        ctx->submitter.immediate([&](VkCommandBuffer cmd) { gpuInteraction.record(cmd, {}, {}, params, tick); });
    EXPECT_EQ(gpuInteraction.stats().dispatches, 0u) << "no active field: no GPU recovery work at all";
    EXPECT_EQ(gpuInteraction.stats().uploadBytes, 0u);

    // One active field: only its plants change, every other field's records stay byte-identical.
    std::vector<uint32_t> active = {2};
    auto contacts = makeContacts(tile, active, 1, params);
    ASSERT_FALSE(contacts.empty());
    ctx->submitter.immediate([&](VkCommandBuffer cmd) { gpuInteraction.record(cmd, contacts, active, params, 0); });
    EXPECT_EQ(gpuInteraction.stats().fieldsDispatched, 1u);
    std::vector<gpu::PlantDynamic> after = gpuInteraction.readDynamics();
    const FieldVegetation& field = tile.fields[2];
    for (size_t p = 0; p < after.size(); ++p) {
        bool inField = p >= field.firstPlant && p < field.firstPlant + field.plantCount();
        if (!inField) {
            ASSERT_EQ(0, std::memcmp(&after[p], &before[p], sizeof(gpu::PlantDynamic))) << "plant " << p;
        }
    }
}
