// WorldTiles: tiles made resident around interest points, evicted behind them, generated alone or in any order on any
// thread count bitwise alike, seams without gap or double plants, tracks kept across eviction, save / restore, and
// memory under the budget over a 2 km flight. CPU only; small tiles and a low density keep it fast.
#include "scene/world_tiles.h"
#include "vegetation/records.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <thread>

using namespace sward;
using namespace sward::test;

namespace {

// 16 x 16 tiles of 100 m (4 x 4 fields each), about 0.9 plants per m^2.
Scene worldScene(nlohmann::json world = nlohmann::json::object(), double density = 0.05) {
    nlohmann::json json = {{"seed", 5},
                           {"terrain", {{"size", 100}, {"spacing", 2}, {"amplitude", 6}}},
                           {"vegetation", {{"density_multiplier", density}}},
                           {"world", {{"tiles", {16, 16}}, {"load_radius", 60}, {"evict_radius", 120}}}};
    json["world"].update(world);
    return parseScene(json, "<world test>");
}

glm::dvec2 centreOf(TileCoord t, double size = 100.0) {
    return {(t.x + 0.5) * size, (t.y + 0.5) * size};
}

template <class T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameTile(const WorldTile& a, const WorldTile& b) {
    ASSERT_EQ(a.coord, b.coord);
    EXPECT_TRUE(sameBytes(a.ground.heightfield()->heights(), b.ground.heightfield()->heights()));
    ASSERT_EQ(a.vegetation.fields.size(), b.vegetation.fields.size());
    for (size_t f = 0; f < a.vegetation.fields.size(); ++f) {
        const FieldVegetation &x = a.vegetation.fields[f], &y = b.vegetation.fields[f];
        ASSERT_TRUE(sameBytes(x.staticRecords, y.staticRecords)) << "field " << f;
        ASSERT_TRUE(sameBytes(x.dynamicRecords, y.dynamicRecords)) << "field " << f;
        ASSERT_TRUE(sameBytes(x.clusters, y.clusters)) << "field " << f;
        EXPECT_EQ(x.origin, y.origin);
    }
    EXPECT_EQ(a.bytes, b.bytes);
}

gpu::PlantDynamic felled() {
    return encodePlantDynamic(PlantMotion{.bend = {0.0f, 0.9f}, .state = gpu::kPlantStateFelled});
}

// Fells every plant of field 5 of the tile: a track.
void makeTrack(WorldTile& tile) {
    FieldVegetation& field = tile.vegetation.fields[5];
    ASSERT_GT(field.plantCount(), 0u);
    std::fill(field.dynamicRecords.begin(), field.dynamicRecords.end(), felled());
    field.timeStamp = 42;
}

bool hasTrack(const WorldTile& tile) {
    const FieldVegetation& field = tile.vegetation.fields[5];
    return sameBytes(field.dynamicRecords, std::vector<gpu::PlantDynamic>(field.plantCount(), felled())) &&
           field.timeStamp == 42;
}

} // namespace

TEST(WorldTiles, ATileIsTheSameAloneAfterItsNeighboursAndOnAnyThreadCount) {
    const TileCoord target{3, 5};
    WorldTiles alone(worldScene({{"load_radius", 10}, {"evict_radius", 20}}), 1);
    const glm::dvec2 centre = centreOf(target);
    alone.waitFor(std::span(&centre, 1));
    ASSERT_EQ(alone.residentTiles(), std::vector<TileCoord>{target});

    // Neighbours first, in another order, then the target among them, on two threads.
    WorldTiles after(worldScene(), 2);
    for (TileCoord n : {TileCoord{4, 6}, TileCoord{2, 4}, TileCoord{4, 5}}) {
        const glm::dvec2 p = centreOf(n);
        after.request(std::span(&p, 1));
        after.waitFor(std::span(&p, 1));
    }
    const glm::dvec2 near = centre + glm::dvec2(45.0, 45.0);
    after.waitFor(std::span(&near, 1));
    ASSERT_NE(after.find(target), nullptr);
    EXPECT_GT(after.residentCount(), 1u);
    expectSameTile(*alone.find(target), *after.find(target));
    expectSameTile(*alone.find(target), generateWorldTile(alone.scene(), target, 2));
}

TEST(WorldTiles, TilesWithinTheLoadRadiusComeAndThoseBeyondTheEvictRadiusGo) {
    WorldTiles world(worldScene());
    glm::dvec2 p(250.0, 250.0); // centre of tile (2, 2): 60 m reaches its four neighbours, not the corners (71 m)
    world.waitFor(std::span(&p, 1));
    EXPECT_EQ(world.residentTiles(), (std::vector<TileCoord>{{2, 1}, {1, 2}, {2, 2}, {3, 2}, {2, 3}}));
    p.x += 50.0; // (3, 1) and (3, 3) come; (1, 2) lies 100 m away, inside the evict radius: kept
    world.waitFor(std::span(&p, 1));
    EXPECT_NE(world.find({1, 2}), nullptr);
    EXPECT_NE(world.find({3, 3}), nullptr);
    EXPECT_EQ(world.stats().evicted, 0u);
    p.x += 100.0; // (1, 2) is now 200 m away
    world.waitFor(std::span(&p, 1));
    EXPECT_EQ(world.find({1, 2}), nullptr);
    EXPECT_GT(world.stats().evicted, 0u);
    // Outside the world nothing is wanted, and every tile goes.
    const glm::dvec2 far(-5000.0, -5000.0);
    world.waitFor(std::span(&far, 1));
    EXPECT_EQ(world.residentCount(), 0u);
    EXPECT_EQ(world.residentBytes(), 0u);
}

TEST(WorldTiles, ATrackSurvivesEvictionAndReload) {
    WorldTiles world(worldScene());
    const TileCoord a{3, 3};
    glm::dvec2 p = centreOf(a);
    world.waitFor(std::span(&p, 1));
    makeTrack(*world.find(a));
    EXPECT_EQ(world.keptStateBytes(), 0u);
    p.x += 600.0;
    world.waitFor(std::span(&p, 1));
    ASSERT_EQ(world.find(a), nullptr);
    EXPECT_GT(world.keptStateBytes(), 0u);
    EXPECT_LT(world.keptStateBytes(), world.residentBytes()); // one touched field, not the tile
    p.x -= 600.0;
    world.waitFor(std::span(&p, 1));
    ASSERT_NE(world.find(a), nullptr);
    EXPECT_TRUE(hasTrack(*world.find(a)));
    EXPECT_EQ(world.stats().restored, 1u);
    // Only that field was kept: the others are as generated.
    const WorldTile fresh = generateWorldTile(world.scene(), a, 0);
    for (size_t f = 0; f < fresh.vegetation.fields.size(); ++f) {
        if (f == 5) continue;
        EXPECT_TRUE(
            sameBytes(fresh.vegetation.fields[f].dynamicRecords, world.find(a)->vegetation.fields[f].dynamicRecords));
    }
}

TEST(WorldTiles, SaveAndRestoreCoverResidentAndEvictedTiles) {
    const std::string path = (tempDir() / "world.state").string();
    const TileCoord a{3, 3}, b{9, 3};
    {
        WorldTiles world(worldScene());
        glm::dvec2 p = centreOf(a);
        world.waitFor(std::span(&p, 1));
        makeTrack(*world.find(a));
        p = centreOf(b); // a is evicted, its track kept
        world.waitFor(std::span(&p, 1));
        ASSERT_EQ(world.find(a), nullptr);
        makeTrack(*world.find(b));
        world.saveState(path, 1234);
    }
    WorldTiles world(worldScene());
    glm::dvec2 p = centreOf(b);
    world.waitFor(std::span(&p, 1));
    EXPECT_FALSE(hasTrack(*world.find(b)));
    EXPECT_EQ(world.restoreState(path), 1234u);
    EXPECT_TRUE(hasTrack(*world.find(b)));
    p = centreOf(a);
    world.waitFor(std::span(&p, 1));
    EXPECT_TRUE(hasTrack(*world.find(a)));
    // A state of another world is refused by name.
    WorldTiles other(worldScene({{"tiles", {8, 8}}}));
    EXPECT_NE(errorOf([&] { other.restoreState(path); }).find("belongs to a world of 16 x 16 tiles"),
              std::string::npos);
}

TEST(WorldTiles, RequestAndPollNeverWaitAndEndWithTheTilesWaitForMakes) {
    WorldTiles streamed(worldScene(), 1), waited(worldScene(), 2);
    const glm::dvec2 p(420.0, 730.0);
    const auto start = std::chrono::steady_clock::now();
    streamed.request(std::span(&p, 1));
    streamed.poll();
    EXPECT_GT(streamed.pendingTiles(), 0u); // it returned before the tiles were made
    while (streamed.pendingTiles() > 0 && std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        streamed.poll();
    }
    streamed.poll();
    waited.waitFor(std::span(&p, 1));
    ASSERT_EQ(streamed.residentTiles(), waited.residentTiles());
    for (TileCoord t : waited.residentTiles()) expectSameTile(*streamed.find(t), *waited.find(t));
}

TEST(WorldTiles, SeamsBetweenTilesHaveNoGapAndNoDoublePlants) {
    WorldTiles world(worldScene({{"load_radius", 10}}, 0.5), 0);
    const glm::dvec2 border(400.0, 550.0); // between tiles (3, 5) and (4, 5)
    world.waitFor(std::span(&border, 1));
    ASSERT_NE(world.find({3, 5}), nullptr);
    ASSERT_NE(world.find({4, 5}), nullptr);
    // Plants near x = 400 in half-metre strips, by tile.
    std::array<uint32_t, 8> strips{}; // [398, 398.5), ..., [399.5, 400), [400, 400.5), ... [401.5, 402)
    std::vector<glm::vec2> west, east;
    for (TileCoord t : {TileCoord{3, 5}, TileCoord{4, 5}}) {
        for (const FieldVegetation& f : world.find(t)->vegetation.fields)
            for (const gpu::PlantStatic& r : f.staticRecords) {
                const glm::vec2 xy =
                    decodePlanarPosition(r.position & 0xffffu, r.position >> 16, f.origin, f.positionStep);
                // Every plant lies in its own tile's square: none is placed twice across the border.
                ASSERT_EQ(xy.x < 400.0f, t.x == 3) << xy.x;
                if (xy.x < 398.0f || xy.x >= 402.0f) continue;
                ++strips.at(size_t((xy.x - 398.0f) * 2.0f));
                (t.x == 3 ? west : east).push_back(xy);
            }
    }
    const double inner = (strips[0] + strips[1] + strips[2] + strips[5] + strips[6] + strips[7]) / 6.0;
    ASSERT_GT(inner, 100.0);
    EXPECT_NEAR(strips[3] / inner, 1.0, 0.2) << "the strip west of the border";
    EXPECT_NEAR(strips[4] / inner, 1.0, 0.2) << "the strip east of the border";
    float closest = 1e9f;
    for (glm::vec2 w : west)
        if (w.x > 399.5f)
            for (glm::vec2 e : east)
                if (e.x < 400.5f) closest = std::min(closest, glm::distance(w, e));
    EXPECT_GT(closest, 1e-3f) << "two plants of different tiles at one spot";
}

TEST(WorldTiles, MemoryStaysUnderTheBudgetOverA2kmFlight) {
    // 16 x 16 tiles of 125 m (a 2 x 2 km world), flown straight across along y = 1000 m in 25 m steps.
    nlohmann::json json = {
        {"seed", 5},
        {"terrain", {{"size", 125}, {"spacing", 5}}},
        {"vegetation", {{"density_multiplier", 0.02}}},
        {"world", {{"tiles", {16, 16}}, {"load_radius", 100}, {"evict_radius", 150}, {"memory_budget_mib", 4}}}};
    WorldTiles world(parseScene(json, "<flight>"));
    const uint64_t budget = world.scene().world.memoryBudgetBytes;
    uint64_t most = 0;
    for (double x = 0.0; x <= 2000.0; x += 25.0) {
        const glm::dvec2 p(x, 1000.0);
        world.waitFor(std::span(&p, 1));
        ASSERT_LE(world.residentBytes(), budget) << "at x = " << x;
        most = std::max(most, world.residentBytes());
    }
    EXPECT_GT(world.stats().evicted, 20u);
    EXPECT_GT(world.stats().generated, 30u);
    EXPECT_GT(most, budget / 8); // the budget is not vacuous
}

TEST(WorldTiles, ResidentMemoryDependsOnTheResidentTilesNotOnTheWorldSize) {
    WorldTiles small(worldScene({{"tiles", {4, 4}}})), large(worldScene({{"tiles", {16, 16}}}));
    const glm::dvec2 p(250.0, 250.0);
    small.waitFor(std::span(&p, 1));
    large.waitFor(std::span(&p, 1));
    EXPECT_EQ(small.residentTiles(), large.residentTiles());
    EXPECT_EQ(small.residentBytes(), large.residentBytes());
}

TEST(WorldTiles, TheExampleWorldLoadsAlongItsFlight) {
    Scene scene = loadScene(std::string(SWARD_SOURCE_DIR) + "/examples/world.json");
    EXPECT_EQ(scene.world.tilesX * scene.vegetation.tileSize, 8000.0f); // 8 x 8 km
    const Ground flat(Heightfield(2, 2, 1e4f, glm::vec2(0.0f), std::vector<float>(4, 0.0f)));
    const PathParams& path = scene.camera.path;
    const double duration = scene.sequence.frames * scene.sequence.timeStep;
    const glm::dvec2 start(pathPose(path, flat, 0.0).position), end(pathPose(path, flat, duration).position);
    EXPECT_NEAR(glm::distance(start, end), 2000.0, 1e-6); // a 2 km flight
    scene.vegetation.densityMultiplier = 0.002f;          // the tiles, not the plants, are under test here
    WorldTiles world(std::move(scene));
    world.waitFor(std::span(&start, 1));
    EXPECT_GE(world.residentCount(), 4u);
    EXPECT_LE(world.residentCount(), 9u);
}

TEST(WorldTiles, InterestPointsFarApartBeyondTheBudgetAreAnErrorThatChangesNothing) {
    WorldTiles world(worldScene({{"memory_budget_mib", 5}}));
    const glm::dvec2 one(250.0, 250.0);
    world.waitFor(std::span(&one, 1));
    const std::vector<TileCoord> before = world.residentTiles();
    const std::vector<glm::dvec2> six = {{250, 250}, {850, 250}, {1450, 250}, {250, 850}, {850, 850}, {1450, 850}};
    const std::string error = errorOf([&] { world.waitFor(six); });
    EXPECT_NE(error.find("of 6 interest points need"), std::string::npos) << error;
    EXPECT_NE(error.find("over 'world.memory_budget_mib' (5 MiB)"), std::string::npos) << error;
    EXPECT_EQ(world.residentTiles(), before);
    EXPECT_EQ(world.stats().evicted, 0u);
}
