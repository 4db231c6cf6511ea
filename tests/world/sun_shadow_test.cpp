// Cascaded sun shadows: where the cascades end, that every receiver lies inside its cascade's map, and that a map
// neither changes texel size as the camera turns nor slides by a fraction of a texel as it moves.
#include "world/sun_shadow.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sward;

namespace {

const glm::dvec3 kToSun = glm::normalize(glm::dvec3(0.4, -0.5, 0.6));

ShadowCascadeParams meadowParams() {
    return ShadowCascadeParams{.cascades = 3, .firstDistance = 50.0, .lastDistance = 154.0, .mapSize = 2048,
                               .heightRange = 14.0};
}

// Map coordinates of `p` in `cascade`: texels across (x, y) and depth (reversed Z, 1 nearest the sun).
glm::dvec3 mapTexel(const ShadowCascade& cascade, const glm::dvec3& p, uint32_t size) {
    const glm::dvec4 ndc = cascade.viewProj * glm::dvec4(p, 1.0);
    return {(ndc.x * 0.5 + 0.5) * size, (ndc.y * 0.5 + 0.5) * size, ndc.z};
}

} // namespace

TEST(SunShadow, CascadesStartAtTheShadowDistanceAndEndWhereThePlantsEnd) {
    const std::vector<double> ends = shadowSplits(meadowParams());
    ASSERT_EQ(ends.size(), 3u);
    EXPECT_EQ(ends.front(), 50.0);
    EXPECT_EQ(ends.back(), 154.0);
    EXPECT_NEAR(ends[1], std::sqrt(50.0 * 154.0), 1e-9); // geometric between the two
    // The maps lie side by side in one row.
    EXPECT_EQ(shadowMapExtent(meadowParams()), glm::uvec2(3 * 2048, 2048));
    const Camera camera = Camera::lookAt({0, 0, 2}, {10, 10, 0}, {0, 0, 1}, 60.0, 640, 480);
    const std::vector<ShadowCascade> cascades = fitShadowCascades(camera, kToSun, meadowParams());
    EXPECT_EQ(cascades[2].mapOffset, 4096u);
    EXPECT_EQ(cascades[2].mapSize, 2048u);
    ShadowCascadeParams single = meadowParams();
    single.cascades = 1;
    EXPECT_EQ(shadowSplits(single), std::vector<double>{50.0});
    ShadowCascadeParams reachesFar = meadowParams();
    reachesFar.firstDistance = 200.0;
    EXPECT_EQ(shadowSplits(reachesFar), std::vector<double>{200.0});
}

TEST(SunShadow, FarBillboardsFallIntoTheLastCascadeAlone) {
    // Far billboards from 38 m, casters reach 4 m: the cascades before the last end 1 m short of 38 - 4 m.
    ShadowCascadeParams params = meadowParams();
    params.farPlantsFrom = 38.0;
    params.casterMargin = 4.0;
    EXPECT_EQ(shadowSplits(params), (std::vector<double>{33.0, 154.0})); // shadow_distance 50 reaches beyond it
    params.firstDistance = 20.0;
    const std::vector<double> ends = shadowSplits(params);
    ASSERT_EQ(ends.size(), 3u);
    EXPECT_EQ(ends[0], 20.0);
    EXPECT_EQ(ends[1], 33.0);
    EXPECT_EQ(ends[2], 154.0);
    // A shadow distance just short of the far billboards' cascade would leave a 31-33 m shell between them: the first
    // cascade reaches 33 m instead (each shell ends at least 1.5 times farther than the one before).
    params.firstDistance = 31.0;
    EXPECT_EQ(shadowSplits(params), (std::vector<double>{33.0, 154.0}));
    params.firstDistance = 22.0; // 33 / 22 = 1.5: still three
    EXPECT_EQ(shadowSplits(params).size(), 3u);
    params.cascades = 4; // 20 -> 33 m in two steps would be 1.28 a step: one step
    params.firstDistance = 20.0;
    EXPECT_EQ(shadowSplits(params), (std::vector<double>{20.0, 33.0, 154.0}));
}

TEST(SunShadow, EveryPointOfTheFrustumLiesInsideTheMapOfItsShell) {
    const ShadowCascadeParams params = meadowParams();
    for (const glm::dvec3 target : {glm::dvec3(15, 30, 0), glm::dvec3(0, 1, -60), glm::dvec3(-40, -2, 5)}) {
        const Camera camera = Camera::lookAt({0, 0, 60}, glm::dvec3(0, 0, 60) + target, {0, 0, 1}, 60.0, 1280, 720);
        const std::vector<ShadowCascade> cascades = fitShadowCascades(camera, kToSun, params);
        ASSERT_EQ(cascades.size(), 3u);
        for (const ShadowCascade& cascade : cascades)
            for (double u = 0.0; u <= 1280.0; u += 160.0)
                for (double v = 0.0; v <= 720.0; v += 90.0)
                    for (double t = 0.0; t <= 1.0; t += 0.125) {
                        const glm::dvec3 ray = glm::normalize(camera.ray(u, v));
                        const glm::dvec3 p =
                            camera.position + ray * (cascade.firstReceiver + t * (cascade.end - cascade.firstReceiver));
                        const glm::dvec3 texel = mapTexel(cascade, p, cascade.mapSize);
                        // Inside by more than the caster margin (the radius holds it beyond the shell).
                        const double margin = params.casterMargin / (2.0 * cascade.radius) * cascade.mapSize - 1.0;
                        EXPECT_GT(texel.x, margin);
                        EXPECT_LT(texel.x, cascade.mapSize - margin);
                        EXPECT_GT(texel.y, margin);
                        EXPECT_LT(texel.y, cascade.mapSize - margin);
                        EXPECT_GT(texel.z, 0.0);
                        EXPECT_LT(texel.z, 1.0);
                    }
    }
}

TEST(SunShadow, AMapKeepsItsTexelSizeAndGridAsTheCameraMovesAndTurns) {
    const ShadowCascadeParams params = meadowParams();
    const Camera a = Camera::lookAt({10, 20, 2}, {30, 50, 0}, {0, 0, 1}, 60.0, 1280, 720);
    const Camera b = Camera::lookAt({10.37, 20.91, 2.13}, {-20, 45, 0}, {0, 0, 1}, 60.0, 1280, 720);
    const std::vector<ShadowCascade> ca = fitShadowCascades(a, kToSun, params);
    const std::vector<ShadowCascade> cb = fitShadowCascades(b, kToSun, params);
    const glm::dvec3 p(12.3, 23.4, 0.5); // in the first shell of both cameras
    for (size_t k = 0; k < ca.size(); ++k) {
        EXPECT_EQ(ca[k].radius, cb[k].radius);
        // The same world point falls at the same place within its texel in both maps: the grid did not slide.
        const glm::dvec3 ta = mapTexel(ca[k], p, ca[k].mapSize), tb = mapTexel(cb[k], p, cb[k].mapSize);
        EXPECT_NEAR(ta.x - std::floor(ta.x + 1e-7), tb.x - std::floor(tb.x + 1e-7), 1e-5) << "cascade " << k;
        EXPECT_NEAR(ta.y - std::floor(ta.y + 1e-7), tb.y - std::floor(tb.y + 1e-7), 1e-5) << "cascade " << k;
    }
}
