// GPU interaction update (contacts + damped spring) against its CPU reference; idle fields cost nothing.
#include "gpu_test.h"

#include "common/hash.h"
#include "interaction/interaction.h"
#include "render/interaction_gpu.h"
#include "vegetation/records.h"
#include "scene/scene.h"

#include <cstring>

using namespace sward;
using sward::test::GpuTest;

namespace {

Scene smallScene() {
    return parseScene(nlohmann::json::parse(R"({"seed": 3, "terrain": {"size": 50, "spacing": 2}})"), "t");
}

// 50 x 50 m: 2 x 2 fields.
VegetationTile smallTile() {
    Scene scene = smallScene();
    return buildVegetation(scene, buildTerrain(scene), 2);
}

bool sameBytes(const std::vector<gpu::PlantDynamic>& a, const std::vector<gpu::PlantDynamic>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::PlantDynamic)) == 0;
}

// Colliders of tick t in the world-driven tests: a sphere rolling through field 0 (x, y in [0, 25)) for the first
// `rolling` ticks, sitting on the terrain.
std::vector<Collider> rollingSphere(const Ground& terrain, uint64_t t, uint64_t rolling) {
    if (t >= rolling) return {};
    glm::vec2 xy(4.0f + 0.4f * float(t), 12.0f);
    return {makeSphere(7, {xy, terrain.height(xy) + 0.3f}, 0.6f, 0.4f)};
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
        // In two runs, as the collision pass leaves a tick's contacts (a run per touched field): the upload joins them.
        const auto owned = std::make_shared<const std::vector<gpu::PlantContact>>(contacts);
        const std::span<const gpu::PlantContact> all(*owned);
        const TickContacts runs(owned, {all.first(all.size() / 2), all.subspan(all.size() / 2)});
        ctx->submitter.immediate(
            [&](VkCommandBuffer cmd) { gpuInteraction.record(cmd, runs, active, params, uint32_t(tick)); });
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
    ctx->submitter.immediate(
        [&](VkCommandBuffer cmd) { gpuInteraction.record(cmd, TickContacts(contacts), active, params, 0); });
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

// The whole loop, InteractionWorld -> InteractionGpu, against InteractionWorld -> simulateOnCpu: a sphere rolls
// through field 0 and leaves. Only field 0 is ever dispatched; the GPU follows the CPU reference within 1e-5; once
// the field has recovered it turns inactive, its plants are back at rest and no tick records GPU work any more.
TEST_F(GpuTest, WorldLoopDispatchesOnlyTouchedFieldsAndStopsAfterRecovery) {
    Scene scene = smallScene();
    Ground terrain = buildTerrain(scene);
    VegetationTile tile = buildVegetation(scene, terrain, 2);
    ASSERT_EQ(tile.fields.size(), 4u);
    VegetationBuffers buffers(*ctx, tile);
    InteractionGpu gpuInteraction(*ctx, buffers);
    InteractionParams params;
    params.recovery.restTicks = 40;
    InteractionWorld world(tile, scene.vegetation, params, 2);
    const std::vector<gpu::PlantDynamic> initial = world.initialDynamics();
    std::vector<gpu::PlantDynamic> cpu = initial;
    ASSERT_TRUE(sameBytes(gpuInteraction.readDynamics(), initial));

    uint64_t expectedDispatches = 0, expectedFields = 0, lastActive = 0;
    size_t contacts = 0;
    for (uint64_t t = 0; t < 120; ++t) {
        TickResult r = world.step(rollingSphere(terrain, t, 20));
        for (uint32_t f : r.activeFields) ASSERT_EQ(f, 0u) << "tick " << t << ": an untouched field is active";
        contacts += r.contacts.size();
        ctx->submitter.immediate([&](VkCommandBuffer cmd) {
            gpuInteraction.record(cmd, r.contacts, r.activeFields, params.recovery, uint32_t(t));
        });
        simulateOnCpu(cpu, r, r.activeFields, tile, params.recovery);
        expectedDispatches += (r.contacts.empty() ? 0 : 1) + (r.activeFields.empty() ? 0 : 1);
        expectedFields += r.activeFields.size();
        if (!r.activeFields.empty()) lastActive = t;
        ASSERT_EQ(gpuInteraction.stats().dispatches, expectedDispatches) << "tick " << t;
        ASSERT_EQ(gpuInteraction.stats().fieldsDispatched, expectedFields) << "tick " << t;
        if (t != 10 && t != 30 && t != 119) continue;
        std::vector<gpu::PlantDynamic> gpu = gpuInteraction.readDynamics();
        size_t bent = 0;
        for (size_t p = 0; p < cpu.size(); ++p) {
            PlantMotion a = decodePlantDynamic(gpu[p]), b = decodePlantDynamic(cpu[p]);
            ASSERT_NEAR(a.bend.x, b.bend.x, 1e-5f) << "plant " << p << " tick " << t;
            ASSERT_NEAR(a.bend.y, b.bend.y, 1e-5f) << "plant " << p << " tick " << t;
            ASSERT_EQ(a.state, b.state) << "plant " << p << " tick " << t;
            bent += a.bend != glm::vec2(0.0f);
            if (p >= tile.fields[1].firstPlant) {
                ASSERT_EQ(0, std::memcmp(&gpu[p], &initial[p], sizeof(gpu::PlantDynamic))) << "untouched plant " << p;
            }
        }
        if (t == 10) {
            EXPECT_GT(bent, 50u) << "the sphere must bend plants";
        }
    }
    EXPECT_GT(contacts, 150u);
    // Field 0 was active until restTicks after the last contact (tick 19), then never again.
    EXPECT_EQ(lastActive, 19u + params.recovery.restTicks - 1);
    EXPECT_TRUE(world.activeFields().empty());
    EXPECT_TRUE(sameBytes(gpuInteraction.readDynamics(), initial)) << "recovered plants are back at exact rest";
}

// Save -> restore -> continue with the GPU holding the dynamic state: bitwise identical to an uninterrupted run.
TEST_F(GpuTest, SaveRestoreContinueOnTheGpuIsBitwiseIdentical) {
    Scene scene = smallScene();
    Ground terrain = buildTerrain(scene);
    VegetationTile tile = buildVegetation(scene, terrain, 2);
    const InteractionParams params;
    const std::string path = sward::test::tempDir("recovery-state") + "/state.bin";
    auto collidersAt = [&](uint64_t t) {
        std::vector<Collider> c = makeGusts(2, 8, {{0, 0, 0.0f}, {50, 50, 0.6f}}, t);
        std::vector<Collider> sphere = rollingSphere(terrain, t, 60);
        c.insert(c.end(), sphere.begin(), sphere.end());
        glm::vec2 wheel(30.0f, 3.0f + 0.3f * float(t));
        float z = terrain.height(wheel) + 0.4f;
        c.push_back(makeCapsule(1, {wheel, z}, {wheel + glm::vec2(0.3f, 0.0f), z}, 0.4f, 3.0f)); // fells
        return c;
    };
    auto tick = [&](InteractionWorld& world, InteractionGpu& gpu) {
        TickResult r = world.step(collidersAt(world.tick()));
        ctx->submitter.immediate(
            [&](VkCommandBuffer cmd) { gpu.record(cmd, r.contacts, r.activeFields, params.recovery, uint32_t(r.tick)); });
    };

    VegetationBuffers straightBuffers(*ctx, tile), resumedBuffers(*ctx, tile);
    InteractionGpu straightGpu(*ctx, straightBuffers), resumedGpu(*ctx, resumedBuffers);
    InteractionWorld straight(tile, scene.vegetation, params), first(tile, scene.vegetation, params);
    for (int t = 0; t < 45; ++t) {
        tick(straight, straightGpu);
        tick(first, resumedGpu);
    }
    first.saveState(path, resumedGpu.readDynamics(), {});
    // A new world and a scrambled GPU state: the restore must bring back everything.
    InteractionWorld resumed(tile, scene.vegetation, params, 2);
    resumedGpu.writeDynamics(resumed.initialDynamics());
    resumedGpu.writeDynamics(resumed.restoreState(path).dynamics);
    EXPECT_EQ(resumed.tick(), 45u);
    for (int t = 45; t < 120; ++t) {
        tick(straight, straightGpu);
        tick(resumed, resumedGpu);
    }
    std::vector<gpu::PlantDynamic> a = straightGpu.readDynamics(), b = resumedGpu.readDynamics();
    EXPECT_TRUE(sameBytes(a, b));
    EXPECT_EQ(straight.activeFields(), resumed.activeFields());
    size_t felled = 0;
    for (const gpu::PlantDynamic& d : a) felled += decodePlantDynamic(d).state == gpu::kPlantStateFelled;
    EXPECT_GT(felled, 50u) << "the run must leave a track";
}
