// The CPU collision pass: contacts, felling, cutting, threads. CPU only.
#include "common/hash.h"
#include "interaction/collider_grid.h"
#include "interaction_world.h"
#include "test_files.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

using namespace sward;
using namespace sward::test;

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
        const std::vector<gpu::PlantContact> list = r.contacts.flatten();
        for (size_t i = 0; i < list.size(); ++i) {
            const gpu::PlantContact& c = list[i];
            if (i > 0) {
                ASSERT_LT(list[i - 1].plant, c.plant);
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
        for (const auto& c : r.contacts.flatten()) ASSERT_EQ(c.flags, gpu::kContactFell);
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

// The paper fells a plant whose "collision forces reach a defined maximum or [which] exceeds a maximum bend": a push
// too light to fell by force fells a plant it bends beyond the category's max_bend, and only that plant.
TEST(Collision, ALightPushBendingAPlantBeyondItsMaxBendFellsIt) {
    const RecoveryParams recovery;
    CategoryInteraction response; // fell force 0.6, push gain 2
    response.maxBend = 0.4f;
    const glm::vec3 base(0.0f), nearBase(0.15f, 0.0f, 0.0f);
    // Force 0.3 < 0.6. The sphere (r 0.3, centre 0.3 m up, 0.1 m beside the stem) presses 0.2 m into a 0.5 m plant:
    // bend 2 * 0.3 * 0.2 / 0.5 = 0.24; into the plant 0.15 m further on only 0.05 m: bend 0.06.
    const Collider sphere = makeSphere(1, {-0.1f, 0.0f, 0.3f}, 0.3f, 0.3f);
    const PlantTouch pressed = touchPlant(sphere, base, 0.5f, response, recovery);
    EXPECT_EQ(pressed.kind, gpu::kContactPush) << "bend 0.24 is below max_bend 0.4";
    response.maxBend = 0.2f;
    const PlantTouch felled = touchPlant(sphere, base, 0.5f, response, recovery);
    EXPECT_EQ(felled.kind, gpu::kContactFell) << "bend 0.24 is beyond max_bend 0.2";
    EXPECT_NEAR(glm::length(felled.push), recovery.fellBend, 1e-5f);
    EXPECT_GT(felled.push.x, 0.0f) << "felled away from the sphere";
    EXPECT_EQ(touchPlant(sphere, nearBase, 0.5f, response, recovery).kind, gpu::kContactPush) << "bend 0.06";
    response.maxBend = INFINITY; // the default: force alone decides, as before
    EXPECT_EQ(touchPlant(sphere, base, 0.5f, response, recovery).kind, gpu::kContactPush);
    Collider gust = sphere;
    gust.kind = ColliderKind::Gust;
    response.maxBend = 0.2f;
    EXPECT_EQ(touchPlant(gust, base, 0.5f, response, recovery).kind, gpu::kContactPush) << "air never fells";
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

// The pass's fast paths (cells under each collider, four stems at a time, spheres apart) against the definition:
// every plant of a mixed meadow (three categories, each with its own gain and fell force, one with a maximum bend)
// against every collider with touchPlant, combined in (id, input) order with combineTouches. Every shape and kind,
// overlapping colliders.
TEST(Collision, ContactsEqualThePerPlantDefinitionForEveryShapeKindAndCategory) {
    Ground ground(Heightfield(26, 26, 2.0f, glm::vec2(0.0f), std::vector<float>(26 * 26, 0.0f)));
    const VegetationParams vegetation = tileParams(50.0f);
    const VegetationTile tile = generateTile(ground, GrassMap(1, 1, 3, {1.0f, 1.0f, 1.0f}, "mixed meadow"),
                                             vegetation, {}, 2);
    InteractionParams params;
    for (uint32_t c = 0; c < params.categories.size(); ++c) {
        params.categories[c].pushGain = 0.7f + 0.9f * float(c);
        params.categories[c].fellForce = 0.3f + 0.2f * float(c);
    }
    params.categories[2].maxBend = 0.9f; // heavy bends fell the flowers too
    std::vector<Collider> colliders;
    for (uint32_t k = 0; k < 40; ++k) { // overlapping spheres of every kind, some heavy enough to fell
        const ColliderKind kind = std::array{ColliderKind::Push, ColliderKind::Gust, ColliderKind::Mower}[k % 3];
        const glm::vec3 centre{3.0f + 1.1f * float(k), 4.0f + 0.37f * float(k * k % 97), 0.1f + 0.02f * float(k % 9)};
        Collider sphere = makeSphere(k / 2, centre, 0.3f + 0.05f * float(k % 7), 0.2f + 0.1f * float(k % 6), kind);
        colliders.push_back(kind == ColliderKind::Mower ? makeMower(sphere, 0.02f * float(k % 5)) : sphere);
    }
    colliders.push_back(makeSphere(7, {12.0f, 20.0f, 0.2f}, 1.5f, 0.5f)); // big, over several cells and clusters
    colliders.push_back(makeCapsule(50, {20, 30, 0.3f}, {24, 31, 0.4f}, 0.5f, 0.9f));
    colliders.push_back(makeBox(51, {35, 12, 0.1f}, {0.8f, 0.4f, 0.2f}, glm::mat3(1.0f), 0.4f));
    colliders.push_back(makeDownwash(52, {40, 40, 2.0f}, 1.2f, 2.5f, 0.6f));

    InteractionWorld world(tile, vegetation, params, 2);
    const TickResult result = world.step(colliders);

    std::vector<uint32_t> order(colliders.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return colliders[a].id < colliders[b].id; });
    std::vector<gpu::PlantContact> expected;
    std::vector<PlantTouch> touches;
    for (uint32_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        for (uint32_t i = 0; i < field.plantCount(); ++i) {
            const PlantInstance plant = decodePlantStatic(field.staticRecords[i]);
            const glm::vec3 base = decodePlantPosition(field.staticRecords[i], field.origin, field.positionStep);
            const float height =
                vegetation.categories[plant.category].height * float(plant.size) / gpu::kPlantSizeDivisor;
            touches.clear();
            for (uint32_t c : order) {
                const CategoryInteraction& response = params.categories[plant.category];
                const PlantTouch t = touchPlant(colliders[c], base, height, response, params.recovery);
                if (t.kind != 0) touches.push_back(t);
            }
            if (touches.empty()) continue;
            gpu::PlantContact contact = combineTouches(touches, params.recovery);
            contact.plant = field.firstPlant + i;
            contact.field = f;
            expected.push_back(contact);
        }
    }
    std::array<uint32_t, 4> kinds{};
    for (const gpu::PlantContact& c : expected) ++kinds[c.flags & 3u];
    EXPECT_GT(kinds[gpu::kContactPush], 500u);
    EXPECT_GT(kinds[gpu::kContactCut], 50u);
    EXPECT_GT(kinds[gpu::kContactFell], 50u);
    const std::vector<gpu::PlantContact> contacts = result.contacts.flatten();
    ASSERT_EQ(contacts.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_TRUE(sameBytes(std::span(&contacts[i], 1), std::span(&expected[i], 1)))
            << "contact " << i << " of plant " << expected[i].plant;
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

// The worst case: one colliding sphere on every 5 x 5 m cluster of a full 500 x 500 m tile at 16 plants/m^2
// (400 fields x 25 colliders). Prints the collision time (issue 17: <= 2 ms on 2 cores; measured by sward-bench collide).
// A tick's contacts lie in the buffers the pass's fields wrote (TickContacts): a result kept while the pass runs
// on must not change, however many results the caller keeps, and they must equal a pass whose results are dropped.
TEST(Collision, KeptContactsStayUnchangedWhileThePassRunsOn) {
    const VegetationTile& tile = smallTile();
    InteractionWorld keeping(tile, tileParams(50), {}, 2), dropping(tile, tileParams(50), {}, 2);
    std::vector<TickResult> kept;
    std::vector<std::vector<gpu::PlantContact>> copies;
    for (uint32_t t = 0; t < 12; ++t) {
        std::vector<Collider> colliders = makeGusts(7, 30, {{0, 0, 0.0f}, {50, 50, 0.5f}}, t);
        colliders.push_back(makeSphere(40, {5.0f + 3.0f * float(t), 25.0f, 0.2f}, 0.8f, 0.4f));
        TickResult r = keeping.step(colliders);
        ASSERT_TRUE(sameBytes(r.contacts, dropping.step(colliders).contacts)) << "tick " << t;
        ASSERT_GT(r.contacts.runs().size(), 1u);
        copies.push_back(r.contacts.flatten());
        // Keep every result for the first ticks, then only every third: the pass must never write into a set of
        // buffers a kept result lies in, nor lose one it still uses.
        if (t < 4 || t % 3 == 0)
            kept.push_back(std::move(r));
        else
            copies.pop_back();
    }
    ASSERT_EQ(kept.size(), copies.size());
    for (size_t i = 0; i < kept.size(); ++i)
        EXPECT_TRUE(sameBytes(kept[i].contacts.flatten(), copies[i])) << "kept result " << i;
}

TEST(TickContacts, JoinsItsRunsInOrderAndDropsEmptyOnes) {
    auto contact = [](uint32_t plant) { return gpu::PlantContact{plant, 0u, gpu::kContactPush, 0u}; };
    auto owned = std::make_shared<const std::vector<gpu::PlantContact>>(
        std::vector<gpu::PlantContact>{contact(1), contact(2), contact(5), contact(9), contact(12)});
    const std::span<const gpu::PlantContact> all(*owned);
    const TickContacts contacts(owned, {all.first(2), all.subspan(2, 0), all.subspan(2, 1), all.subspan(3)});
    EXPECT_EQ(contacts.size(), 5u);
    EXPECT_EQ(contacts.runs().size(), 3u);
    std::vector<uint32_t> plants;
    for (const gpu::PlantContact& c : contacts.flatten()) plants.push_back(c.plant);
    EXPECT_EQ(plants, (std::vector<uint32_t>{1, 2, 5, 9, 12}));
    EXPECT_TRUE(TickContacts().empty());
    EXPECT_TRUE(TickContacts(std::vector<gpu::PlantContact>{}).runs().empty());
    const TickContacts copied(std::vector<gpu::PlantContact>{contact(3), contact(4)});
    EXPECT_EQ(copied.runs().size(), 1u);
    EXPECT_EQ(copied.flatten()[1].plant, 4u);
}

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
        for (const gpu::PlantContact& c : r.contacts.flatten())
            for (size_t b = 0; b < sizeof(c); ++b) hash = (hash ^ reinterpret_cast<const uint8_t*>(&c)[b]) * 1099511628211ull;
        std::printf("[ perf ] contacts hash %016llx\n", (unsigned long long)hash);
        EXPECT_EQ(r.touchedFields.size(), 400u);
        EXPECT_EQ(r.touchedClusters.size(), 10000u);
        std::printf("[ perf ] 400 fields x 25 colliders, %u thread(s): median %.3f ms, best %.3f ms; %zu contacts "
                    "(%llu bytes), %u clusters tested, %llu plants tested of %u; binning %.3f ms\n",
                    threads, ms[ms.size() / 2], ms[0], r.contacts.size(), (unsigned long long)r.stats.contactBytes,
                    r.stats.clustersTested, (unsigned long long)r.stats.plantsTested, world.plantCount(),
                    r.stats.buildMs);
    }
}

// ColliderGrid against brute force: for every field, exactly the kept colliders whose boxes overlap the field's box,
// ascending. Colliders of every size and shape, on field edges and corners, beyond the tile and above the grass, given
// out of id order with repeated ids.
TEST(ColliderGrid, ListsExactlyTheCollidersOverlappingEachFieldInRankOrder) {
    const VegetationTile tile = makeTile(100.0f);
    ASSERT_EQ(tile.fieldsPerSide, 4u);
    std::vector<Collider> colliders;
    HashStream random{hashKey({17})};
    for (uint32_t i = 0; i < 600; ++i) {
        const uint32_t id = (i * 7919u) % 500u; // out of order, some ids twice
        // Centres from 10 m before the tile to 10 m beyond it, a quarter of them snapped onto field edges.
        glm::vec3 c(random.nextFloat() * 120.0f - 10.0f, random.nextFloat() * 120.0f - 10.0f,
                    random.nextFloat() * 3.0f - 0.5f);
        if (i % 4 == 0) c.x = 25.0f * std::round(c.x / 25.0f);
        if (i % 8 == 0) c.y = 25.0f * std::round(c.y / 25.0f);
        const float r = i % 50 == 0 ? 40.0f : 0.05f + random.nextFloat() * 2.0f;
        switch (i % 3) {
        case 0:
            colliders.push_back(makeSphere(id, c, r, 0.4f));
            break;
        case 1:
            colliders.push_back(makeCapsule(id, c, c + glm::vec3(30.0f * random.nextFloat(), -3.0f, 0.2f), r, 0.4f));
            break;
        default:
            colliders.push_back(makeBox(id, c, {r, 0.5f * r, 0.3f}, glm::mat3(1.0f), 0.4f));
            break;
        }
    }
    colliders.push_back(makeSphere(1000, {50.0f, 50.0f, 30.0f}, 1.0f, 0.4f)); // above the grass: never kept

    // Ranks in (id, input) order and each field's lists, its shares' one after the other, exactly the kept colliders
    // whose boxes overlap the field's, for colliders out of id order (ranked by a sort) and in it (as they come), in
    // one share or several binned in any order.
    std::vector<Collider> inIdOrder = colliders;
    std::stable_sort(inIdOrder.begin(), inIdOrder.end(),
                     [](const Collider& a, const Collider& b) { return a.id < b.id; });
    const Aabb keep{glm::vec3(-1e3f, -1e3f, -1.0f), glm::vec3(1e3f, 1e3f, 2.0f)};
    for (const std::vector<Collider>* input : {&colliders, &inIdOrder})
        for (uint32_t shares : {1u, 2u, 3u}) {
            SCOPED_TRACE(std::string(input == &colliders ? "out of id order" : "in id order") + ", shares " +
                         std::to_string(shares));
            ColliderGrid grid(tile);
            grid.begin(*input, keep, shares);
            for (uint32_t k = shares; k-- > 0;) grid.binShare(k);
            ASSERT_GT(grid.size(), 500u);
            ASSERT_LT(grid.size(), input->size());
            size_t pairs = 0, multiField = 0;
            std::vector<uint32_t> fieldsOf(grid.size(), 0);
            for (uint32_t f = 0; f < tile.fields.size(); ++f) {
                const Aabb box{tile.fields[f].boundsMin, tile.fields[f].boundsMax};
                std::vector<uint32_t> expected, listed;
                for (uint32_t r = 0; r < grid.size(); ++r) {
                    if (r > 0) {
                        const uint32_t i = grid.inputIndex(r - 1), j = grid.inputIndex(r);
                        const Collider &a = (*input)[i], &b = (*input)[j];
                        ASSERT_TRUE(a.id < b.id || (a.id == b.id && i < j));
                    }
                    if (grid.bounds(r).overlaps(box)) expected.push_back(r);
                }
                for (uint32_t k = 0; k < shares; ++k) {
                    const std::span<const uint32_t> ranks = grid.ranks(f, k);
                    listed.insert(listed.end(), ranks.begin(), ranks.end());
                }
                ASSERT_EQ(listed, expected) << "field " << f;
                for (uint32_t r : expected) ++fieldsOf[r];
                pairs += expected.size();
            }
            for (uint32_t n : fieldsOf) multiField += n > 1 ? 1 : 0;
            EXPECT_GT(pairs, 450u);
            EXPECT_GT(multiField, 50u); // many colliders straddle field edges
        }
}
