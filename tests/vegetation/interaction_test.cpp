// Acceptance tests of issue 6, CPU side: colliders, the collision pass, field activity, the CPU reference of the
// recovery (simulateOnCpu) and save / restore. Everything runs without a GPU.
#include "interaction.h"
#include "placement.h"
#include "records.h"

#include "test_files.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

using namespace sward;
using namespace sward::test;

namespace {

constexpr uint32_t kGrass = 1;

// Flat ground at z = 0 with uniform grass (16 plants/m^2) over a square tile of `size` metres.
VegetationParams tileParams(float size) {
    VegetationParams p;
    p.tileSize = size;
    p.seed = 3;
    return p;
}

VegetationTile makeTile(float size) {
    const uint32_t n = uint32_t(size / 2.0f) + 1;
    Ground ground(Heightfield(n, n, 2.0f, glm::vec2(0.0f), std::vector<float>(size_t(n) * n, 0.0f)));
    GrassMap grass(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    return generateTile(ground, grass, tileParams(size), {}, 2);
}

// 50 x 50 m: 2 x 2 fields, about 40,000 plants.
const VegetationTile& smallTile() {
    static const VegetationTile tile = makeTile(50.0f);
    return tile;
}

struct PlantInfo {
    glm::vec3 base;
    float height;
    uint32_t field;
};

std::vector<PlantInfo> plantInfos(const VegetationTile& tile, const VegetationParams& params) {
    std::vector<PlantInfo> out;
    for (uint32_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        for (const gpu::PlantStatic& r : field.staticRecords) {
            PlantInstance p = decodePlantStatic(r);
            out.push_back({decodePlantPosition(r, field.origin, field.positionStep),
                           params.categories[p.category].height * float(p.size) / gpu::kPlantSizeDivisor, f});
        }
    }
    return out;
}

glm::vec2 pushOf(const gpu::PlantContact& c) {
    return {float(int16_t(c.push & 0xffffu)) / 32767.0f, float(int16_t(c.push >> 16)) / 32767.0f};
}

bool sameBytes(const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

// A world plus the CPU stand-in for the GPU's dynamic buffer.
struct Sim {
    const VegetationTile* tile;
    InteractionWorld world;
    std::vector<gpu::PlantDynamic> dynamics;
    TickResult step(std::span<const Collider> colliders) {
        TickResult r = world.step(colliders);
        simulateOnCpu(dynamics, r, r.activeFields, *tile, world.params().recovery);
        return r;
    }
};

Sim makeSim(const VegetationTile& tile, const InteractionParams& params = {}, uint32_t threads = 1) {
    InteractionWorld world(tile, tileParams(tile.size), params, threads);
    auto dynamics = world.initialDynamics();
    return Sim{&tile, std::move(world), std::move(dynamics)};
}

// A sphere rolling along +x at y through the small tile's field 0 and 1, one position per tick.
Collider sphereAt(uint32_t tick, float force = 0.4f) {
    return makeSphere(7, {4.0f + 0.25f * float(tick), 12.0f, 0.3f}, 0.6f, force);
}

} // namespace

TEST(Collider, SignedDistanceAxisPointAndBoundsOfEachShape) {
    Collider s = makeSphere(1, {1, 2, 3}, 0.5f, 1.0f);
    EXPECT_FLOAT_EQ(signedDistance(s, {1, 2, 4}), 0.5f);
    EXPECT_FLOAT_EQ(signedDistance(s, {1, 2, 3}), -0.5f);
    EXPECT_EQ(axisPoint(s, {9, 9, 9}), glm::vec3(1, 2, 3));

    Collider c = makeCapsule(2, {0, 0, 0}, {0, 4, 0}, 1.0f, 1.0f);
    EXPECT_FLOAT_EQ(signedDistance(c, {2, 2, 0}), 1.0f);
    EXPECT_FLOAT_EQ(signedDistance(c, {0, 6, 0}), 1.0f);
    EXPECT_EQ(axisPoint(c, {3, 1, 0}), glm::vec3(0, 1, 0));
    EXPECT_EQ(worldBounds(c).min, glm::vec3(-1, -1, -1));
    EXPECT_EQ(worldBounds(c).max, glm::vec3(1, 5, 1));

    // A 2 x 1 x 1 box turned 90 degrees about z: its long axis lies along world y.
    glm::mat3 turn(glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1));
    Collider b = makeBox(3, {0, 0, 0}, {1.0f, 0.5f, 0.5f}, turn, 1.0f);
    EXPECT_NEAR(signedDistance(b, {0, 1.5f, 0}), 0.5f, 1e-6f);
    EXPECT_NEAR(signedDistance(b, {1.5f, 0, 0}), 1.0f, 1e-6f);
    EXPECT_NEAR(signedDistance(b, {0, 0, 0}), -0.5f, 1e-6f);
    EXPECT_NEAR(worldBounds(b).max.x, 0.5f, 1e-6f);
    EXPECT_NEAR(worldBounds(b).max.y, 1.0f, 1e-6f);
    // The core of the box is its long mid-line: a point beside it is pushed sideways, not along it.
    glm::vec3 a = axisPoint(b, {0.4f, 0.3f, 0.0f});
    EXPECT_NEAR(a.x, 0.0f, 1e-6f);
    EXPECT_NEAR(a.y, 0.3f, 1e-6f);
}

TEST(Collider, GustsAreDeterministicPerSeedAndDrift) {
    Aabb area{{0, 0, 0.2f}, {50, 50, 0.6f}};
    auto a = makeGusts(5, 20, area, 100), b = makeGusts(5, 20, area, 100), c = makeGusts(6, 20, area, 100);
    auto later = makeGusts(5, 20, area, 101);
    ASSERT_EQ(a.size(), 20u);
    int differentSeed = 0, moved = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].kind, ColliderKind::Gust);
        EXPECT_EQ(a[i].centre, b[i].centre);
        EXPECT_EQ(a[i].radius, b[i].radius);
        EXPECT_EQ(a[i].force, b[i].force);
        differentSeed += a[i].centre != c[i].centre || a[i].radius != c[i].radius;
        moved += a[i].centre != later[i].centre;
        EXPECT_GE(a[i].radius, 1.0f);
        EXPECT_LE(a[i].radius, 4.0f);
        EXPECT_GE(a[i].centre.x, 0.0f);
        EXPECT_LE(a[i].centre.x, 50.0f);
        EXPECT_GE(a[i].centre.z, 0.2f);
        EXPECT_LE(a[i].centre.z, 0.6f);
    }
    EXPECT_EQ(differentSeed, 20);
    EXPECT_EQ(moved, 20);
}

TEST(Collider, DownwashPushesOutwardWeakerAwayFromTheAxis) {
    Collider d = makeDownwash(1, {10, 10, 3.0f}, 2.0f, 3.5f, 0.3f);
    InteractionParams params;
    auto bendAt = [&](float dx) {
        PlantTouch t = touchPlant(d, {10.0f + dx, 10.0f, 0.0f}, 0.4f, params.categories[kGrass], params.recovery);
        EXPECT_EQ(t.kind, gpu::kContactPush);
        EXPECT_GT(t.push.x, 0.0f);
        EXPECT_NEAR(t.push.y, 0.0f, 1e-6f);
        return glm::length(t.push);
    };
    EXPECT_GT(bendAt(0.3f), bendAt(1.0f));
    EXPECT_GT(bendAt(1.0f), bendAt(1.8f));
    // Air never fells, however strong.
    d.force = 50.0f;
    EXPECT_EQ(touchPlant(d, {10.5f, 10, 0}, 0.4f, params.categories[kGrass], params.recovery).kind, gpu::kContactPush);
    EXPECT_EQ(touchPlant(d, {12.5f, 10, 0}, 0.4f, params.categories[kGrass], params.recovery).kind, 0u);
}

TEST(Collision, CombinesTouchesFellOverCutOverPushAndClampsThePush) {
    RecoveryParams r;
    PlantTouch push{{0.8f, 0.0f}, gpu::kContactPush, gpu::kPlantUncut};
    PlantTouch push2{{0.0f, 0.8f}, gpu::kContactPush, gpu::kPlantUncut};
    PlantTouch cut{{0.1f, 0.0f}, gpu::kContactCut, 40};
    PlantTouch cut2{{0.1f, 0.0f}, gpu::kContactCut, 30};
    PlantTouch fell{{0.0f, -0.9f}, gpu::kContactFell, gpu::kPlantUncut};

    std::vector<PlantTouch> two{push, push2};
    gpu::PlantContact c = combineTouches(two, r);
    EXPECT_EQ(c.flags, gpu::kContactPush);
    EXPECT_NEAR(glm::length(pushOf(c)), 0.95f, 1e-4f);
    EXPECT_NEAR(pushOf(c).x, pushOf(c).y, 1e-4f);

    std::vector<PlantTouch> cuts{push, cut, cut2};
    c = combineTouches(cuts, r);
    EXPECT_EQ(c.flags & 15u, gpu::kContactCut);
    EXPECT_EQ((c.flags >> 8) & 255u, 30u);
    EXPECT_NEAR(pushOf(c).x, 0.95f, 1e-4f); // 0.8 + 0.1 + 0.1, clamped

    std::vector<PlantTouch> all{cut, fell, push};
    c = combineTouches(all, r);
    EXPECT_EQ(c.flags & 15u, gpu::kContactFell);
    EXPECT_NEAR(glm::length(pushOf(c)), r.fellBend, 1e-4f);
}

TEST(Collision, SphereBendsOnlyTheTouchedPlantsAwayFromItsCentreAndTheyRecoverExactly) {
    const VegetationTile& tile = smallTile();
    const auto plants = plantInfos(tile, tileParams(50));
    Sim sim = makeSim(tile);
    const auto rest = sim.dynamics;
    size_t contacts = 0, nonZero = 0;
    for (uint32_t t = 0; t < 80; ++t) {
        Collider s = sphereAt(t);
        TickResult r = sim.step(std::span(&s, 1));
        std::vector<uint8_t> touched(plants.size(), 0);
        for (size_t i = 0; i < r.contacts.size(); ++i) {
            const gpu::PlantContact& c = r.contacts[i];
            if (i > 0) {
                ASSERT_LT(r.contacts[i - 1].plant, c.plant);
            }
            ASSERT_EQ(c.flags, gpu::kContactPush);
            const PlantInfo& p = plants[c.plant];
            ASSERT_EQ(c.field, p.field);
            touched[c.plant] = 1;
            EXPECT_LE(glm::length(p.base - s.centre), s.radius + p.height);
            glm::vec2 away = glm::vec2(p.base) - glm::vec2(s.centre);
            float d = glm::dot(pushOf(c), away);
            EXPECT_GE(d, 0.0f);
            nonZero += c.push != 0 && d > 0.0f;
        }
        contacts += r.contacts.size();
        // Every plant whose base is inside the sphere is touched.
        for (size_t i = 0; i < plants.size(); ++i)
            if (glm::length(plants[i].base - s.centre) < s.radius - 1e-3f) {
                EXPECT_TRUE(touched[i]) << i;
            }
    }
    EXPECT_GT(contacts, 1000u);
    EXPECT_GT(nonZero, contacts * 9 / 10);
    size_t bent = 0;
    for (const auto& d : sim.dynamics) bent += d.bend != 0;
    EXPECT_GT(bent, 100u);

    // The sphere has gone: within restTicks every plant is back at exact rest and every field inactive.
    for (uint32_t t = 0; t < sim.world.params().recovery.restTicks; ++t) sim.step({});
    EXPECT_TRUE(sameBytes(sim.dynamics, rest));
    EXPECT_TRUE(sim.world.activeFields().empty());
}

TEST(Collision, HeavyWheelLeavesFelledPlantsThatStayDownFor1000Ticks) {
    const VegetationTile& tile = smallTile();
    Sim sim = makeSim(tile);
    // A 0.3 m wide wheel of radius 0.4 m rolling along +x, far heavier than the grass's fell threshold.
    for (uint32_t t = 0; t < 160; ++t) {
        float x = 5.0f + 0.25f * float(t);
        Collider wheel = makeCapsule(1, {x, 30.0f, 0.4f}, {x, 30.3f, 0.4f}, 0.4f, 3.0f);
        TickResult r = sim.step(std::span(&wheel, 1));
        for (const auto& c : r.contacts) ASSERT_EQ(c.flags, gpu::kContactFell);
    }
    const auto afterPass = sim.dynamics;
    size_t felled = 0;
    for (const auto& d : afterPass) {
        PlantMotion m = decodePlantDynamic(d);
        if (m.state != gpu::kPlantStateFelled) continue;
        ++felled;
        EXPECT_NEAR(glm::length(m.bend), sim.world.params().recovery.fellBend, 1e-3f);
    }
    EXPECT_GT(felled, 500u);
    for (uint32_t t = 0; t < 1000; ++t) sim.step({});
    EXPECT_TRUE(sameBytes(sim.dynamics, afterPass)); // tracks persist: felled plants never move again
    EXPECT_TRUE(sim.world.activeFields().empty());
}

TEST(Collision, MowerLeavesShorterCutPlants) {
    const VegetationTile& tile = smallTile();
    Sim sim = makeSim(tile);
    for (uint32_t t = 0; t < 100; ++t) {
        Collider blade = makeMower(
            makeBox(2, {30.0f, 5.0f + 0.2f * float(t), 0.1f}, {0.6f, 0.3f, 0.06f}, glm::mat3(1.0f), 0.3f), 0.1f);
        sim.step(std::span(&blade, 1));
    }
    for (uint32_t t = 0; t < sim.world.params().recovery.restTicks; ++t) sim.step({});
    size_t cut = 0;
    for (const auto& d : sim.dynamics) {
        PlantMotion m = decodePlantDynamic(d);
        if (m.state == gpu::kPlantStateCut) {
            ++cut;
            EXPECT_LT(d.state >> 24, 255u);
            EXPECT_LT(m.cutFraction, 1.0f);
            EXPECT_EQ(d.bend, 0u); // sprung back, but stays short
        } else {
            EXPECT_EQ(d.state >> 24, 255u);
        }
    }
    EXPECT_GT(cut, 300u); // 1.2 m x 20 m swath at 16 plants/m^2: about 380
}

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

TEST(Collision, TenThousandCollidersAboveTheGrassCostNothing) {
    const VegetationTile& tile = smallTile();
    InteractionWorld world(tile, tileParams(50), {}, 2);
    std::vector<Collider> colliders;
    for (uint32_t i = 0; i < 10000; ++i)
        colliders.push_back(makeSphere(i, {float(i % 100) * 0.5f, float(i / 100) * 0.5f, 20.0f}, 0.5f, 1.0f));
    double best = 1e9;
    for (int t = 0; t < 20; ++t) {
        TickResult r = world.step(colliders);
        EXPECT_TRUE(r.contacts.empty());
        EXPECT_TRUE(r.activeFields.empty());
        EXPECT_EQ(r.stats.collidersKept, 0u);
        EXPECT_EQ(r.stats.colliders, 10000u);
        best = std::min(best, r.stats.cpuMs);
    }
    std::printf("[ perf ] 10,000 idle colliders: %.3f ms per tick (best of 20)\n", best);
}

TEST(Collision, IdenticalContactsWithOneAndFourThreads) {
    const VegetationTile& tile = smallTile();
    InteractionWorld one(tile, tileParams(50), {}, 1), four(tile, tileParams(50), {}, 4);
    size_t total = 0;
    for (uint32_t t = 0; t < 30; ++t) {
        std::vector<Collider> colliders = makeGusts(9, 30, {{0, 0, 0.0f}, {50, 50, 0.5f}}, t);
        colliders.push_back(makeCapsule(3, {2.0f + t, 20, 0.4f}, {2.0f + t, 20.3f, 0.4f}, 0.4f, 3.0f));
        colliders.push_back(makeMower(makeSphere(4, {40, 2.0f + t, 0.2f}, 0.5f, 0.2f), 0.05f));
        colliders.push_back(makeSphere(3, {2.0f + t, 20.5f, 0.2f}, 0.6f, 0.3f)); // same id: input order decides
        TickResult a = one.step(colliders), b = four.step(colliders);
        ASSERT_TRUE(sameBytes(a.contacts, b.contacts));
        EXPECT_EQ(a.touchedFields, b.touchedFields);
        EXPECT_EQ(a.touchedClusters, b.touchedClusters);
        EXPECT_EQ(a.activeFields, b.activeFields);
        EXPECT_EQ(a.stats.plantsTested, b.stats.plantsTested);
        total += a.contacts.size();
    }
    EXPECT_GT(total, 10000u);
}

// One world per thread count, plus one whose pool is resized between ticks: every tick's contacts, fields and
// statistics, and the simulated records, must be bitwise the same.
TEST(Collision, BitwiseIdenticalWithOneTwoAndThreeThreads) {
    const VegetationTile& tile = smallTile();
    Sim one = makeSim(tile, {}, 1), two = makeSim(tile, {}, 2), three = makeSim(tile, {}, 3);
    Sim switching = makeSim(tile, {}, 1);
    size_t total = 0;
    for (uint32_t t = 0; t < 40; ++t) {
        std::vector<Collider> colliders = makeGusts(4, 25, {{0, 0, 0.0f}, {50, 50, 0.5f}}, t);
        for (uint32_t k = 0; k < 20; ++k) // one sphere per 5 x 5 m cluster of a row, as in the benchmark
            colliders.push_back(makeSphere(100 + k, {2.5f + 2.5f * float(k) + 0.3f * float(t % 7), 7.5f, 0.3f}, 0.5f,
                                           0.4f));
        colliders.push_back(makeCapsule(3, {2.0f + t, 33, 0.4f}, {2.0f + t, 33.3f, 0.4f}, 0.4f, 3.0f));
        colliders.push_back(makeMower(makeBox(5, {44, 2.0f + t, 0.1f}, {0.6f, 0.3f, 0.06f}, glm::mat3(1.0f), 0.3f), 0.1f));
        switching.world.setThreads(1 + t % 3);
        TickResult a = one.step(colliders), b = two.step(colliders), c = three.step(colliders),
                   d = switching.step(colliders);
        for (const TickResult* r : {&b, &c, &d}) {
            ASSERT_TRUE(sameBytes(a.contacts, r->contacts)) << "tick " << t;
            EXPECT_EQ(a.touchedFields, r->touchedFields);
            EXPECT_EQ(a.touchedClusters, r->touchedClusters);
            EXPECT_EQ(a.activeFields, r->activeFields);
            EXPECT_EQ(a.stats.plantsTested, r->stats.plantsTested);
            EXPECT_EQ(a.stats.clustersTested, r->stats.clustersTested);
            EXPECT_EQ(a.stats.fieldsTested, r->stats.fieldsTested);
        }
        total += a.contacts.size();
    }
    EXPECT_GT(total, 5000u);
    EXPECT_TRUE(sameBytes(one.dynamics, two.dynamics));
    EXPECT_TRUE(sameBytes(one.dynamics, three.dynamics));
    EXPECT_TRUE(sameBytes(one.dynamics, switching.dynamics));
}

TEST(StateFile, SaveRestoreContinueIsBitwiseIdenticalToAnUninterruptedRun) {
    const VegetationTile& tile = smallTile();
    const std::string path = (tempDir() / "state.bin").string();
    auto collidersAt = [](uint32_t t) {
        std::vector<Collider> c = makeGusts(2, 10, {{0, 0, 0.0f}, {50, 50, 0.4f}}, t);
        c.push_back(makeCapsule(1, {3.0f + 0.3f * t, 40, 0.4f}, {3.0f + 0.3f * t, 40.3f, 0.4f}, 0.4f, 3.0f));
        c.push_back(makeMower(makeSphere(2, {45, 3.0f + 0.3f * t, 0.2f}, 0.5f, 0.2f), 0.1f));
        return c;
    };
    Sim straight = makeSim(tile), first = makeSim(tile);
    for (uint32_t t = 0; t < 60; ++t) {
        auto c = collidersAt(t);
        straight.step(c);
        first.step(c);
    }
    first.world.saveState(path, first.dynamics);
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

    Sim resumed = makeSim(tile);
    resumed.dynamics = resumed.world.restoreState(path);
    EXPECT_EQ(resumed.world.tick(), 60u);
    EXPECT_EQ(resumed.world.activeFields(), straight.world.activeFields());
    for (uint32_t t = 60; t < 150; ++t) {
        auto c = collidersAt(t);
        TickResult a = straight.step(c), b = resumed.step(c);
        ASSERT_TRUE(sameBytes(a.contacts, b.contacts));
        ASSERT_EQ(a.activeFields, b.activeFields);
    }
    EXPECT_TRUE(sameBytes(straight.dynamics, resumed.dynamics));
    EXPECT_EQ(straight.world.tick(), resumed.world.tick());
}

TEST(StateFile, CorruptTruncatedOrForeignFilesAreErrorsNamingTheFile) {
    const VegetationTile& tile = smallTile();
    const auto dir = tempDir();
    const std::string path = (dir / "state.bin").string();
    InteractionWorld world(tile, tileParams(50), {});
    world.saveState(path, world.initialDynamics());
    std::vector<char> good;
    {
        std::ifstream in(path, std::ios::binary);
        good.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    auto expectError = [&](const std::vector<char>& bytes, const std::string& needle) {
        const std::string bad = (dir / "bad.bin").string();
        {
            std::ofstream out(bad, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(bytes.size()));
        }
        try {
            world.restoreState(bad);
            ADD_FAILURE() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    auto flipped = good;
    flipped[good.size() / 2] ^= 0x10; // inside the dynamic records
    expectError(flipped, "checksum");
    expectError({good.begin(), good.end() - 100}, "truncated");
    auto longer = good;
    longer.insert(longer.end(), 16, '\0');
    expectError(longer, "size");
    expectError({good.begin(), good.begin() + 20}, "truncated");
    auto magic = good;
    magic[0] = 'X';
    expectError(magic, "magic");
    auto version = good;
    version[8] = 9;
    expectError(version, "version");
    try {
        world.restoreState((dir / "missing.bin").string());
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing.bin"), std::string::npos);
    }
    // A valid file of another tile is refused too.
    InteractionState other = loadInteractionState(path);
    other.dynamics.pop_back();
    saveInteractionState((dir / "other.bin").string(), other);
    EXPECT_THROW(world.restoreState((dir / "other.bin").string()), Error);
    EXPECT_EQ(world.tick(), 0u);
}

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
TEST(CollisionPerf, FourHundredFieldsWithTwentyFiveCollidersEach) {
    const VegetationTile tile = makeTile(500.0f);
    ASSERT_EQ(tile.fields.size(), 400u);
    InteractionWorld world(tile, tileParams(500.0f), {}, 1);
    std::vector<Collider> colliders;
    for (uint32_t y = 0; y < 100; ++y)
        for (uint32_t x = 0; x < 100; ++x)
            colliders.push_back(makeSphere(y * 100 + x, {5.0f * x + 2.5f, 5.0f * y + 2.5f, 0.3f}, 0.5f, 0.4f));
    for (uint32_t threads : {1u, 2u}) {
        world.setThreads(threads);
        std::vector<double> ms;
        TickResult r;
        for (int t = 0; t < 15; ++t) {
            r = world.step(colliders);
            ms.push_back(r.stats.cpuMs);
        }
        std::sort(ms.begin(), ms.end());
        // FNV-1a of the contact bytes: the same figure for every thread count and every optimisation of the pass.
        uint64_t hash = 14695981039346656037ull;
        for (const gpu::PlantContact& c : r.contacts)
            for (size_t b = 0; b < sizeof(c); ++b) hash = (hash ^ reinterpret_cast<const uint8_t*>(&c)[b]) * 1099511628211ull;
        std::printf("[ perf ] contacts hash %016llx\n", (unsigned long long)hash);
        EXPECT_EQ(r.touchedFields.size(), 400u);
        EXPECT_EQ(r.touchedClusters.size(), 10000u);
        std::printf("[ perf ] 400 fields x 25 colliders, %u thread(s): median %.3f ms, best %.3f ms; %zu contacts "
                    "(%llu bytes), %u clusters tested, %llu plants tested of %u; BVH build %.3f ms\n",
                    threads, ms[ms.size() / 2], ms[0], r.contacts.size(), (unsigned long long)r.stats.contactBytes,
                    r.stats.clustersTested, (unsigned long long)r.stats.plantsTested, world.plantCount(),
                    r.stats.buildMs);
    }
}
