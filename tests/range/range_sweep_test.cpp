// Sweeps: bitwise the same on any number of threads, beams where the sensor model puts them, echoes chosen as asked,
// noise and dropout as configured, and the files' layouts read back by their own rules.
#include "range/range_files.h"
#include "range/range_sweep.h"

#include "range_test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace sward {
namespace {

// The uniform patch with one sensor (JSON `sensor`, merged over a fixed mount in the patch's middle).
struct SensorPatch {
    test::UniformPatch patch;
    std::vector<ObjectModel> models;
    std::unique_ptr<RayScene> rays;

    SensorPatch(double density, nlohmann::json sensor, double size = 50.0) {
        nlohmann::json mount = {
            {"position", {size / 2, size / 2, 0.0}}, {"height_above_ground", 1.0}, {"yaw_deg", 30.0}};
        if (!sensor.contains("mount")) sensor["mount"] = mount;
        sensor["name"] = "s";
        patch = test::uniformPatch(density, size, {{"range_sensors", nlohmann::json::array({sensor})}});
        rays = std::make_unique<RayScene>(patch.ground, patch.atlas, patch.scene.vegetation, &patch.tile);
        rays->setPlants(patch.scene.wind, 0.0, {}, {size / 2, size / 2}, 100.0);
    }
    RangeScan sweep(uint32_t threads, uint32_t frame = 0) {
        return sweepSensor(*rays, {patch.scene, patch.ground, models}, 0, frame, 0.0, threads);
    }
};

TEST(RangeSweep, IsBitwiseTheSameOnOneAndTwoThreads) {
    SensorPatch s(6.0, {{"preset", "VLP-16"}, {"sub_rays", 7}, {"dropout", 0.05}, {"angle_step_deg", 1.0}});
    const RangeScan one = s.sweep(1), two = s.sweep(2);
    ASSERT_GT(one.points.size(), 1000u);
    EXPECT_EQ(rangePly(one, "x"), rangePly(two, "x"));
    EXPECT_EQ(semanticKittiLabel(one), semanticKittiLabel(two));
    EXPECT_EQ(one.ranges, two.ranges);
    // Another frame draws other noise.
    EXPECT_NE(rangePly(one, "x"), rangePly(s.sweep(2, 1), "x"));
}

// Over bare flat ground, every downward beam of a fixed LiDAR meets the ground at height / sin(-elevation), and its
// point lies on the ground.
TEST(RangeSweep, BeamsMeetBareGroundWhereTheGeometrySaysTheyDo) {
    SensorPatch s(0.0, {{"preset", "VLP-16"}, {"range_noise_m", 0.0}, {"angle_step_deg", 2.0}}, 150.0);
    const RangeScan scan = s.sweep(2);
    const RangeSensorParams& sensor = s.patch.scene.rangeSensors[0];
    uint32_t checked = 0;
    for (const RangePoint& p : scan.points) {
        const double elevation = sensor.elevationsDegrees[p.ring] * 3.141592653589793 / 180.0;
        ASSERT_LT(elevation, 0.0) << "a beam above the horizon hit flat ground";
        EXPECT_NEAR(p.range, 1.0 / std::sin(-elevation), 1e-4);
        EXPECT_NEAR(p.world.z, s.patch.ground.height({float(p.world.x), float(p.world.y)}), 1e-4);
        EXPECT_EQ(p.label >> gpu::kInstanceBits, gpu::kSemanticGround);
        ++checked;
    }
    EXPECT_EQ(checked, 8u * sensor.columns()); // the 8 rings below the horizon, every column
}

// Range noise has the configured spread; dropout drops the configured share.
TEST(RangeSweep, NoiseAndDropoutFollowTheirParameters) {
    SensorPatch s(0.0, {{"preset", "VLP-16"}, {"range_noise_m", 0.05}, {"dropout", 0.2}, {"angle_step_deg", 0.5}},
                  150.0);
    const RangeScan scan = s.sweep(2);
    const RangeSensorParams& sensor = s.patch.scene.rangeSensors[0];
    double sum = 0.0, squares = 0.0;
    for (const RangePoint& p : scan.points) {
        const double error = p.range - 1.0 / std::sin(-sensor.elevationsDegrees[p.ring] * 3.141592653589793 / 180.0);
        sum += error, squares += error * error;
    }
    const double n = double(scan.points.size()), mean = sum / n, sd = std::sqrt(squares / n - mean * mean);
    const double kept = n / (8.0 * sensor.columns());
    EXPECT_NEAR(mean, 0.0, 0.005);
    EXPECT_NEAR(sd, 0.05, 0.005);
    EXPECT_NEAR(kept, 0.8, 0.02);
}

// A beam wider than a plant in front of the ground splits into two echoes: first the plant, last the ground.
TEST(RangeSweep, FirstAndLastReturnsSeparateAPlantFromTheGroundBehindIt) {
    auto scanWith = [](const char* mode) {
        SensorPatch s(3.0, {{"preset", "VLP-16"},
                            {"divergence_mrad", 60.0},
                            {"sub_rays", 19},
                            {"return", mode},
                            {"range_noise_m", 0.0},
                            {"elevations_deg", {-12.0}},
                            {"angle_step_deg", 0.5}});
        return s.sweep(2);
    };
    const RangeScan first = scanWith("first"), last = scanWith("last"), strongest = scanWith("strongest");
    ASSERT_EQ(first.ranges.size(), last.ranges.size());
    uint32_t split = 0, plantFirst = 0;
    for (size_t b = 0; b < first.ranges.size(); ++b) {
        ASSERT_GT(first.ranges[b], 0.0f);
        EXPECT_LE(first.ranges[b], last.ranges[b]);
        EXPECT_LE(first.ranges[b], strongest.ranges[b]);
        EXPECT_LE(strongest.ranges[b], last.ranges[b]);
        split += last.ranges[b] - first.ranges[b] > 0.5f;
    }
    for (const RangePoint& p : first.points) plantFirst += (p.label >> gpu::kInstanceBits) != gpu::kSemanticGround;
    EXPECT_GT(split, first.ranges.size() / 10); // many beams see a plant and, past it, the ground
    EXPECT_GT(plantFirst, first.points.size() / 5);
}

// The files by their formats' rules: KITTI .bin is x, y, z, intensity floats; a .label's low 16 bits the class; a
// PLY's header names its count; the scan JSON's ranges line up with the scan.
TEST(RangeFiles, LayoutsFollowTheirFormats) {
    SensorPatch s(6.0, {{"preset", "VLP-16"}, {"angle_step_deg", 2.0}});
    const RangeScan scan = s.sweep(2);
    const std::string bin = kittiBin(scan), label = semanticKittiLabel(scan), ply = rangePly(scan, "test");
    ASSERT_EQ(bin.size(), scan.points.size() * 16);
    ASSERT_EQ(label.size(), scan.points.size() * 4);
    for (size_t i = 0; i < scan.points.size(); i += 97) {
        float xyzi[4];
        uint32_t l;
        std::memcpy(xyzi, bin.data() + 16 * i, 16);
        std::memcpy(&l, label.data() + 4 * i, 4);
        EXPECT_EQ(xyzi[0], scan.points[i].sensor.x);
        EXPECT_EQ(xyzi[3], scan.points[i].intensity);
        EXPECT_EQ(l & 0xffffu, scan.points[i].label >> gpu::kInstanceBits);
        EXPECT_EQ((l >> 16) == 0, (scan.points[i].label & 0xffffffu) == 0); // the ground has no instance
    }
    EXPECT_NE(ply.find("element vertex " + std::to_string(scan.points.size()) + "\n"), std::string::npos);
    const size_t header = ply.find("end_header\n") + 11;
    EXPECT_EQ(ply.size() - header, scan.points.size() * (3 * 4 + 3 * 8 + 4 + 4 + 2 + 2 + 1 + 4));

    SensorPatch scanner(6.0, {{"preset", "LMS111"}});
    const RangeScan laser = scanner.sweep(2);
    const nlohmann::json j = nlohmann::json::parse(laserScanJson(scanner.patch.scene.rangeSensors[0], laser));
    ASSERT_EQ(j["ranges"].size(), 541u); // 270 degrees in 0.5 degree steps, both ends
    for (size_t c = 0; c < laser.ranges.size(); ++c) EXPECT_EQ(j["ranges"][c].is_null(), laser.ranges[c] == 0.0f);
}

// A ToF camera's depth is planar (along its axis): over flat bare ground, looking down at 90 degrees, every pixel
// reads the height.
TEST(RangeFiles, TofDepthIsPlanar) {
    SensorPatch s(0.0,
                  {{"preset", "AzureKinect-NFOV"},
                   {"range_noise_m", 0.0},
                   {"resolution", {64, 48}},
                   {"range", {0.1, 10.0}},
                   {"mount", {{"position", {25.0, 25.0, 0.0}}, {"height_above_ground", 2.0}, {"pitch_deg", 90.0}}}});
    const std::vector<float> depth = tofDepth(s.patch.scene.rangeSensors[0], s.sweep(2));
    ASSERT_EQ(depth.size(), 64u * 48u);
    for (float z : depth) EXPECT_NEAR(z, 2.0f, 1e-4f);
}

} // namespace
} // namespace sward

namespace sward {
namespace {

// A LiDAR driving at 20 m/s: each column fires later and from further along; a point's world position is its
// sensor-frame position under the pose of its own firing time, and the sweep's poses in frames.jsonl bracket them.
TEST(RangeSweep, PointsAreTimedAndPlacedByThePoseOfTheirOwnColumn) {
    const nlohmann::json path = {{"points", {{20, 75}, {130, 75}}}, {"speed", 20.0}, {"height_above_ground", 1.0}};
    nlohmann::json sensorJson = {{"preset", "VLP-16"}, {"range_noise_m", 0.0}, {"angle_step_deg", 1.0}};
    sensorJson["mount"] = {{"path", path}};
    SensorPatch s(0.0, sensorJson, 150.0);
    const RangeSensorParams& sensor = s.patch.scene.rangeSensors[0];
    const RangeScan scan = s.sweep(2);
    ASSERT_GT(scan.points.size(), 1000u);
    for (const RangePoint& p : scan.points) {
        EXPECT_FLOAT_EQ(p.time, float(columnTime(sensor, p.column)));
        const glm::dmat4 pose = rangeSensorPose(s.patch.scene, sensor, s.patch.ground, s.models, double(p.time));
        const glm::dvec3 world(pose * glm::dvec4(glm::dvec3(p.sensor), 1.0));
        EXPECT_NEAR(glm::distance(world, p.world), 0.0, 2e-5);
    }
    // 20 m/s for a tenth of a second: the last column fires 2 m further along the path than the first.
    EXPECT_NEAR(scan.endPose[3].x - scan.startPose[3].x, 20.0 * columnTime(sensor, sensor.columns() - 1), 1e-9);
    EXPECT_NEAR(scan.points.back().time, 0.1 * 359.0 / 360.0, 1e-6);
}

} // namespace
} // namespace sward
