#include "scene/range_sensors.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/scene.h"
#include "scene/terrain.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace sward {
namespace {

std::vector<RangeSensorParams> parse(const nlohmann::json& sensors) {
    const nlohmann::json root = {{"range_sensors", sensors}};
    JsonReader reader(root, "test.json");
    return parseRangeSensors(reader);
}

TEST(RangeSensors, PresetsGiveTheirDataSheetLayoutAndKeysOverrideThem) {
    const auto sensors =
        parse({{{"preset", "VLP-16"}, {"mount", {{"position", {1, 2, 0}}}}},
               {{"preset", "VLP-16"}, {"angle_step_deg", 0.4}, {"mount", {{"position", {1, 2, 0}}}}},
               {{"preset", "LMS111"}, {"mount", {{"position", {1, 2, 0}}}}},
               {{"preset", "AzureKinect-NFOV"}, {"resolution", {64, 48}}, {"mount", {{"position", {1, 2, 0}}}}}});
    ASSERT_EQ(sensors.size(), 4u);
    EXPECT_EQ(sensors[0].channels(), 16u);
    EXPECT_EQ(sensors[0].columns(), 1800u); // a full turn in 0.2 degree steps, its first azimuth fired once
    EXPECT_DOUBLE_EQ(sensors[0].elevationsDegrees.front(), -15.0);
    EXPECT_DOUBLE_EQ(sensors[0].elevationsDegrees.back(), 15.0);
    EXPECT_EQ(sensors[0].name, "sensor0");
    EXPECT_EQ(sensors[1].columns(), 900u);
    EXPECT_EQ(sensors[2].type, RangeSensorType::Scanner);
    EXPECT_EQ(sensors[2].columns(), 541u); // -135 .. 135 in 0.5 degree steps, both ends
    EXPECT_EQ(sensors[2].channels(), 1u);
    EXPECT_EQ(sensors[3].columns(), 64u);
    EXPECT_EQ(sensors[3].channels(), 48u);
    // A LiDAR column fires step / 360 of a turn after the one before; a scanner's the same within its window.
    EXPECT_DOUBLE_EQ(columnTime(sensors[0], 900), 0.05);
    EXPECT_DOUBLE_EQ(columnTime(sensors[2], 540), 270.0 / 360.0 / 25.0);
    EXPECT_DOUBLE_EQ(columnTime(sensors[3], 63), 0.0);
}

TEST(RangeSensors, BeamsAndPosesFollowTheSensorFrame) {
    auto sensors = parse(
        {{{"preset", "VLP-16"},
          {"mount", {{"position", {10, 20, 0}}, {"height_above_ground", 1.5}, {"yaw_deg", 90}, {"pitch_deg", 30}}}}});
    const RangeSensorParams& s = sensors[0];
    // Azimuth 0 is +x, azimuth 90 degrees +y (left); ring 0 looks 15 degrees down.
    const glm::dvec3 first = beamDirection(s, 0, 900); // azimuth -180 + 180 = 0
    EXPECT_NEAR(first.x, std::cos(15.0 * M_PI / 180.0), 1e-12);
    EXPECT_NEAR(first.z, -std::sin(15.0 * M_PI / 180.0), 1e-12);
    EXPECT_NEAR(beamDirection(s, 8, 1350).y, std::cos(s.elevationsDegrees[8] * M_PI / 180.0), 1e-12);

    const Scene scene = parseScene(nlohmann::json{{"terrain", {{"size", 50}, {"amplitude", 0}}}}, "flat.json");
    const Ground ground = buildTerrain(scene);
    const glm::dmat4 pose = rangeSensorPose(scene, s, ground, {}, 0.0);
    // Yaw 90: the sensor's +x is world +y, tilted 30 degrees down; its left (+y) is world -x; origin 1.5 m up.
    EXPECT_NEAR(pose[0].y, std::cos(M_PI / 6), 1e-12);
    EXPECT_NEAR(pose[0].z, -0.5, 1e-12);
    EXPECT_NEAR(pose[1].x, -1.0, 1e-12);
    EXPECT_NEAR(pose[3].x, 10.0, 1e-12);
    EXPECT_NEAR(pose[3].z, ground.height({10.0f, 20.0f}) + 1.5, 1e-6);
}

TEST(RangeSensors, RaysAFrameArePricedOverAllSensorsBeforeAnyIsCast) {
    const nlohmann::json tof = {{"type", "tof"}, {"resolution", {4096, 4096}}, {"mount", {{"position", {1, 2, 0}}}}};
    EXPECT_EQ(parse({tof, tof}).size(), 2u) << "2 x 2^24 rays: exactly the limit";
    try {
        parse({tof, tof, tof});
        FAIL() << "three 4096x4096 ToF cameras were accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "test.json: 'range_sensors' cast 50331648 rays a frame (beams x 'sub_rays', "
                                         "all sensors), over the limit of 33554432; lower 'resolution', the channels, "
                                         "'sub_rays' or raise 'angle_step_deg'");
    }
}

} // namespace
} // namespace sward
