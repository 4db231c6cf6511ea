// Beams through grass: transmission falls with plant density and depth as a Beer-Lambert law, and felled or cut
// grass lets more beams through than standing grass.
#include "range/ray_scene.h"

#include "common/hash.h"
#include "range_test_scene.h"
#include "vegetation/records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sward {
namespace {

constexpr double kBeamHeight = 0.1; // metres above the flat ground: inside the 0.5 m grass

// Fraction of horizontal beams at kBeamHeight from hashed points and headings in the patch's middle that meet nothing
// within `depth` metres.
double transmission(const RayScene& rays, double depth, uint32_t beams = 3000) {
    uint32_t through = 0;
    for (uint32_t i = 0; i < beams; ++i) {
        const uint64_t h = hashKey({0x4245455231ull, i});
        const glm::dvec3 origin(15.0 + 20.0 * unitDouble(h), 15.0 + 20.0 * unitDouble(mix64(h)), kBeamHeight);
        const double heading = 2.0 * 3.141592653589793 * unitDouble(mix64(h ^ 77));
        if (!rays.cast(origin, {std::cos(heading), std::sin(heading), 0.0}, 0.0, depth).hit()) ++through;
    }
    return double(through) / beams;
}

TEST(RangePenetration, TransmissionFollowsBeerLambertInDensityAndDepth) {
    const double densities[] = {0.5, 1.0, 2.0, 4.0}, depths[] = {0.25, 0.5, 1.0, 2.0};
    std::vector<glm::dvec3> samples; // (density, depth, transmission)
    for (double density : densities) {
        const auto patch = test::uniformPatch(density);
        RayScene rays(patch.ground, patch.atlas, patch.scene.vegetation, &patch.tile);
        rays.setPlants(patch.scene.wind, 0.0, {}, {25.0, 25.0}, 100.0);
        for (double depth : depths) samples.push_back({density, depth, transmission(rays, depth)});
    }
    // ln T = -k * density * depth, least squares through the origin.
    double num = 0.0, den = 0.0, mean = 0.0;
    for (const glm::dvec3& s : samples) {
        ASSERT_GT(s.z, 0.0) << "no beam got through " << s.y << " m at " << s.x << " plants/m^2";
        num += s.x * s.y * std::log(s.z), den += (s.x * s.y) * (s.x * s.y), mean += s.z;
    }
    const double k = -num / den;
    mean /= double(samples.size());
    double residual = 0.0, total = 0.0;
    for (const glm::dvec3& s : samples) {
        const double model = std::exp(-k * s.x * s.y);
        residual += (s.z - model) * (s.z - model), total += (s.z - mean) * (s.z - mean);
        std::printf("density %5.1f /m^2  depth %4.2f m  transmission %.4f  fit %.4f\n", s.x, s.y, s.z, model);
    }
    const double r2 = 1.0 - residual / total;
    std::printf("Beer-Lambert fit: extinction %.4f m per (plant/m^2), R^2 %.4f\n", k, r2);
    RecordProperty("extinction", std::to_string(k));
    RecordProperty("r_squared", std::to_string(r2));
    EXPECT_GT(k, 0.0);
    EXPECT_GE(r2, 0.95);
    // Denser or deeper grass never lets more through.
    for (size_t i = 1; i < samples.size(); ++i)
        if (samples[i].x == samples[i - 1].x) {
            EXPECT_LE(samples[i].z, samples[i - 1].z);
        }
}

// Every plant of the patch put into one interaction state.
void setState(VegetationTile& tile, uint32_t state, float cutFraction) {
    for (FieldVegetation& field : tile.fields)
        for (uint32_t i = 0; i < field.plantCount(); ++i) {
            const uint64_t h = hashKey({0x5354415445ull, field.firstPlant + i});
            const double a = 2.0 * 3.141592653589793 * unitDouble(h);
            PlantMotion motion;
            motion.state = state;
            motion.cutFraction = cutFraction;
            if (state == gpu::kPlantStateFelled) motion.bend = glm::vec2(std::cos(a), std::sin(a)) * 0.9f;
            field.dynamicRecords[i] = encodePlantDynamic(motion);
        }
}

TEST(RangePenetration, FelledAndCutGrassLetMoreBeamsThrough) {
    auto patch = test::uniformPatch(8.0);
    auto measure = [&]() {
        RayScene rays(patch.ground, patch.atlas, patch.scene.vegetation, &patch.tile);
        rays.setPlants(patch.scene.wind, 0.0, {}, {25.0, 25.0}, 100.0);
        return transmission(rays, 1.0);
    };
    const double standing = measure();
    setState(patch.tile, gpu::kPlantStateFelled, 1.0f);
    const double felled = measure();
    setState(patch.tile, gpu::kPlantStateCut, 0.15f);
    const double cut = measure();
    std::printf("transmission over 1 m at 8 plants/m^2, %.2f m up: standing %.4f, felled %.4f, cut %.4f\n", kBeamHeight,
                standing, felled, cut);
    EXPECT_GT(felled, standing + 0.05);
    EXPECT_GT(cut, standing + 0.05);
}

} // namespace
} // namespace sward
