// Colliders: shapes, gusts, downwash. CPU only.
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
