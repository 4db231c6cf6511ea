// Objects and gusts in a world of several tiles (scene/world_objects.h), on the CPU: an object's ground covers its
// footprint, objects are interest points and their colliders keep their ids, gusts blow only where every tile they
// reach is within view_distance of the camera, near the ground, and are a pure function of the tick and the camera.
#include "scene/world_objects.h"

#include "scene/rover_model.h"
#include "scene/scene.h"
#include "scene/world_tiles.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sward;
using namespace sward::test;

namespace {

// 4 x 2 tiles of 20 m; a rover (scale 2, turned 30 degrees) drives east along y = 10 across x = 20 and 40.
Scene roverWorld(const std::string& dir, uint32_t gusts = 0) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 20, "spacing": 1, "amplitude": 3, "feature_size": 30, "octaves": 2},
        "vegetation": {"tile_size": 20, "field_size": 10},
        "world": {"tiles": [4, 2], "load_radius": 12, "view_distance": 10},
        "lod": {"near": 2, "mid": 4, "far": 7, "band": 2},
        "objects": [{"name": "rover", "model": "rover.gltf", "scale": 2, "yaw_deg": 30,
                     "path": {"points": [[14, 10], [50, 10]], "speed": 3},
                     "colliders": [{"node": "chassis", "shape": "sphere", "radius": 0.5},
                                   {"node": "wheel_fl", "shape": "sphere", "radius": 0.3}]}],
        "sequence": {"time_step": 0.1}
    })");
    if (gusts > 0) json["gusts"] = {{"count", gusts}, {"height", 0.5}};
    return parseScene(json, dir + "/scene.json");
}

class WorldObjects : public ::testing::Test {
protected:
    void SetUp() override {
        dir = tempDir().string();
        saveRoverGltf(dir + "/rover.gltf");
    }
    std::string dir;
};

double distanceToTile(TileCoord t, glm::dvec2 p, double size = 20.0) {
    const double dx = std::max({0.0, t.x * size - p.x, p.x - (t.x + 1) * size});
    const double dy = std::max({0.0, t.y * size - p.y, p.y - (t.y + 1) * size});
    return std::sqrt(dx * dx + dy * dy);
}

} // namespace

// objectPose reads the heights under the footprint's corners: they lie inside the object's ground, so none is clamped
// to its edge, and that ground is the world's lattice (the same heights as latticeGround over a wide window).
TEST_F(WorldObjects, ObjectGroundCoversTheFootprintOnTheWorldLattice) {
    const Scene scene = roverWorld(dir);
    const std::vector<ObjectModel> models = loadObjectModels(scene.objects, scene.source);
    const ObjectParams& rover = scene.objects[0];
    const Ground wide = latticeGround(scene, {0.0, 0.0}, {80.0, 40.0}, 0.0);
    for (double time : {0.0, 1.9, 2.0, 5.5, 10.0}) {
        const Ground ground = objectGround(scene, rover, models[0], time);
        const ObjectPose pose = objectPose(rover, models[0], ground, time);
        for (const glm::vec3 corner : {models[0].boundsMin, models[0].boundsMax})
            for (double sx : {-1.0, 1.0})
                for (double sy : {-1.0, 1.0}) {
                    const glm::dvec2 xy(pose.worldFromModel *
                                        glm::dvec4(sx * std::abs(corner.x), sy * std::abs(corner.y), 0.0, 1.0));
                    EXPECT_GT(xy.x, ground.boundsMin().x) << "time " << time;
                    EXPECT_GT(xy.y, ground.boundsMin().y) << "time " << time;
                    EXPECT_LT(xy.x, ground.boundsMax().x) << "time " << time;
                    EXPECT_LT(xy.y, ground.boundsMax().y) << "time " << time;
                    EXPECT_NEAR(ground.height(glm::vec2(xy)), wide.height(glm::vec2(xy)), 1e-4) << "time " << time;
                }
        // The origin rests on the plane fitted to the ground under the footprint: within the ground's relief there.
        EXPECT_NEAR(pose.position.z, wide.height(glm::vec2(pose.position)), 0.5) << "time " << time;
    }
}

// Objects are interest points, after the vehicles and free colliders; their colliders come after the actors' with
// objectColliders' ids, each on the object's own ground.
TEST_F(WorldObjects, ObjectsAreInterestPointsAndCollideOnTheirGround) {
    const Scene scene = roverWorld(dir);
    const std::vector<ObjectModel> models = loadObjectModels(scene.objects, scene.source);
    const std::vector<glm::dvec2> points = actorPoints(scene, 2.0);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].x, 20.0, 1e-9);
    EXPECT_NEAR(points[0].y, 10.0, 1e-9);
    const std::vector<Collider> colliders = worldColliders(scene, models, 20);
    ASSERT_EQ(colliders.size(), 2u);
    EXPECT_EQ(colliders[0].id, 200000u);
    EXPECT_EQ(colliders[1].id, 200001u);
    const std::vector<Collider> own =
        objectColliders(scene.objects[0], models[0], 0, objectGround(scene, scene.objects[0], models[0], 2.0), 2.0);
    EXPECT_EQ(colliders[0].centre, own[0].centre);
    EXPECT_EQ(colliders[1].centre, own[1].centre);
    // Astride the border at x = 20: the chassis reaches both tiles.
    EXPECT_EQ(tilesReached(scene, colliders[0]).size(), 2u);
}

// Gusts drift over the whole world and blow only where every tile they reach lies within view_distance of the camera,
// their centres 0 .. height above the lattice ground; the same tick and camera give the same gusts.
TEST_F(WorldObjects, GustsBlowOnlyWithinViewDistanceOfTheCameraNearTheGround) {
    const Scene scene = roverWorld(dir, 400);
    uint64_t blowing = 0;
    for (uint64_t tick : {0u, 7u, 50u, 300u}) {
        const glm::dvec2 camera(25.0 + 0.1 * double(tick), 14.0);
        const std::vector<Collider> gusts = worldGusts(scene, tick, camera);
        EXPECT_LT(gusts.size(), 400u) << "the air is calm far from the camera";
        const std::vector<Collider> all =
            makeGusts(scene.actors.gusts.seed, 400, Aabb{glm::vec3(0.0f), glm::vec3(80.0f, 40.0f, 0.5f)}, tick,
                      float(scene.sequence.timeStep));
        uint32_t previous = 0;
        for (const Collider& gust : gusts) {
            EXPECT_EQ(gust.kind, ColliderKind::Gust);
            EXPECT_GE(gust.id, 0x80000000u);
            EXPECT_TRUE(previous == 0 || gust.id > previous) << "in id order";
            previous = gust.id;
            const Collider& drift = all[gust.id - 0x80000000u];
            EXPECT_EQ(glm::vec2(gust.centre), glm::vec2(drift.centre)) << "the world's drift, unchanged in xy";
            EXPECT_EQ(gust.radius, drift.radius);
            for (TileCoord t : tilesReached(scene, gust)) EXPECT_LE(distanceToTile(t, camera), 10.0);
            const glm::dvec2 xy(gust.centre);
            const float ground = latticeGround(scene, xy, xy, 0.0).height(glm::vec2(gust.centre));
            EXPECT_GE(gust.centre.z, ground);
            EXPECT_LE(gust.centre.z, ground + 0.5f + 1e-5f);
        }
        blowing += gusts.size();
        const std::vector<Collider> again = worldGusts(scene, tick, camera);
        ASSERT_EQ(again.size(), gusts.size());
        for (size_t i = 0; i < gusts.size(); ++i) EXPECT_EQ(again[i].centre, gusts[i].centre);
    }
    EXPECT_GT(blowing, 0u) << "gusts blow near the camera";
    EXPECT_TRUE(worldGusts(scene, 0, {1000.0, 1000.0}).empty()) << "a camera far outside the world has no gusts";
}

// The refusals are gone: a world of several tiles takes objects and gusts.
TEST_F(WorldObjects, AWorldOfSeveralTilesTakesObjectsAndGusts) {
    const Scene scene = roverWorld(dir, 3);
    EXPECT_NO_THROW(checkWorldDrawable(scene));
    EXPECT_NO_THROW(checkWorldScene(scene));
}
