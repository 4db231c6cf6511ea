// The closed-loop vehicle model (interaction/vehicle_controller.h): its limits, its turning circle and its exact
// heading arithmetic. CPU only.
#include "interaction/vehicle_controller.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace sward;

namespace {

constexpr double kDt = 0.05;

VehicleState drive(VehicleState s, const VehicleCommand& command, int ticks, const VehicleLimits& limits = {}) {
    for (int i = 0; i < ticks; ++i) s = stepVehicle(s, command, limits, kDt);
    return s;
}

} // namespace

TEST(VehicleController, FullThrottleReachesTheTopSpeedAndNoMore) {
    const VehicleLimits limits;
    VehicleState s = drive({}, {.throttle = 1.0}, 1);
    EXPECT_DOUBLE_EQ(s.speed, limits.acceleration * kDt);
    s = drive(s, {.throttle = 1.0}, 200);
    EXPECT_EQ(s.speed, limits.maxSpeed);
    EXPECT_EQ(drive({}, {.throttle = -1.0}, 200).speed, -limits.maxReverseSpeed);
}

TEST(VehicleController, BrakingStopsAtStandstillWithoutReversing) {
    const VehicleState moving{.speed = 2.0};
    const VehicleState stopped = drive(moving, {.brake = 1.0}, 20);
    EXPECT_EQ(stopped.speed, 0.0);
    // 6 m/s^2 for 2 m/s: stopped within 7 ticks of 0.05 s, having rolled about v^2 / 2a = 0.33 m.
    EXPECT_EQ(drive(moving, {.brake = 1.0}, 7).speed, 0.0);
    EXPECT_GT(stopped.position.x, 0.2);
    EXPECT_LT(stopped.position.x, 0.4);
    // Without throttle the drag slows it too, more gently.
    EXPECT_DOUBLE_EQ(drive(moving, {}, 1).speed, 2.0 - 0.5 * kDt);
}

TEST(VehicleController, FullSteerDrivesTheMinimumTurningCircle) {
    const VehicleLimits limits;
    VehicleState s{.headingDegrees = 90.0, .speed = 1.0};
    // A full circle at 1 m/s: 2 pi r / v seconds; drag off so the speed stays 1.
    const VehicleLimits steady{.drag = 0.0};
    const int ticks = int(std::lround(2.0 * std::numbers::pi * limits.minTurnRadius / kDt));
    double furthest = 0.0;
    for (int i = 0; i < ticks; ++i) {
        s = stepVehicle(s, {.steer = 1.0}, steady, kDt);
        // Turning left from heading +y at the origin: the centre is at (-r, 0).
        furthest = std::max(furthest, std::abs(glm::length(s.position - glm::dvec2(-limits.minTurnRadius, 0.0)) -
                                               limits.minTurnRadius));
    }
    EXPECT_LT(furthest, 1e-3);
    EXPECT_LT(glm::length(s.position), 0.05); // back at the start after one turn
}

TEST(VehicleController, HeadingsMatchLibmWithinRounding) {
    for (int i = -720; i <= 720; ++i) {
        const double degrees = i * 0.5 + 0.123;
        const double radians = degrees * std::numbers::pi / 180.0;
        const glm::dvec2 d = headingDirection(degrees);
        EXPECT_NEAR(d.x, std::cos(radians), 1e-14);
        EXPECT_NEAR(d.y, std::sin(radians), 1e-14);
        const double back = headingDegreesOf(d);
        EXPECT_NEAR(back, std::atan2(d.y, d.x) * 180.0 / std::numbers::pi, 1e-12);
    }
    EXPECT_EQ(headingDegreesOf({-1.0, 0.0}), 180.0);
    EXPECT_EQ(headingDegreesOf({0.0, -2.0}), -90.0);
}

TEST(VehicleController, HeadingStaysInItsRange) {
    VehicleState s{.headingDegrees = 179.0, .speed = 1.0};
    s = stepVehicle(s, {.steer = 1.0}, VehicleLimits{}, 0.1);
    EXPECT_GE(s.headingDegrees, -180.0);
    EXPECT_LT(s.headingDegrees, -175.0);
}

TEST(VehicleController, RefusesControlsOutOfRangeNamingThem) {
    auto message = [](const VehicleCommand& c) { return test::errorOf([&] { checkVehicleCommand(c); }); };
    EXPECT_EQ(message({.throttle = 1.5}), "drive: throttle must be a number from -1 to 1 (got 1.5)");
    EXPECT_EQ(message({.steer = NAN}), "drive: steer must be a number from -1 to 1 (got a value that is not finite)");
    EXPECT_EQ(message({.brake = -0.5}), "drive: brake must be a number from 0 to 1 (got -0.5)");
    EXPECT_EQ(message({.throttle = 1.0, .steer = -1.0, .brake = 1.0}), "");
}
