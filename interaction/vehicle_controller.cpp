#include "interaction/vehicle_controller.h"

#include "common/error.h"
#include "common/exact_math.h"
#include "common/json_reader.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sward {

namespace {

constexpr double kPi = 3.14159265358979323846;

// atan(x) for |x| <= 1: the angle halved twice (atan x = 2 atan(x / (1 + sqrt(1 + x^2))), |x| <= tan(pi / 16) <
// 0.2 then), and 14 terms of its series (the first omitted below 1e-19).
double exactAtan(double x) {
    for (int k = 0; k < 2; ++k) x = x / (1.0 + std::sqrt(1.0 + x * x));
    const double x2 = x * x;
    double sum = 0.0, power = x;
    for (int k = 0; k < 14; ++k) {
        sum += (k % 2 ? -power : power) / double(2 * k + 1);
        power *= x2;
    }
    return 4.0 * sum;
}

// Moves `value` towards 0 by `amount` (>= 0), stopping there.
double towardsZero(double value, double amount) {
    return value > 0.0 ? std::max(value - amount, 0.0) : std::min(value + amount, 0.0);
}

void checkControl(const char* name, double value, double low, double high) {
    require(std::isfinite(value) && value >= low && value <= high,
            std::string("drive: ") + name + " must be a number from " + (low < 0.0 ? "-1" : "0") + " to 1 (got " +
                (std::isfinite(value) ? formatNumber(value) : std::string("a value that is not finite")) + ")");
}

} // namespace

void checkVehicleCommand(const VehicleCommand& command) {
    checkControl("throttle", command.throttle, -1.0, 1.0);
    checkControl("steer", command.steer, -1.0, 1.0);
    checkControl("brake", command.brake, 0.0, 1.0);
}

VehicleState stepVehicle(const VehicleState& state, const VehicleCommand& command, const VehicleLimits& limits,
                         double dt) {
    checkVehicleCommand(command);
    require(std::isfinite(dt) && dt > 0.0, "drive: the time step must be a positive number of seconds");
    double speed = state.speed + command.throttle * limits.acceleration * dt;
    const double deceleration = command.brake * limits.braking + (command.throttle == 0.0 ? limits.drag : 0.0);
    speed = std::clamp(towardsZero(speed, deceleration * dt), -limits.maxReverseSpeed, limits.maxSpeed);
    const double turnDegrees = speed * dt * command.steer / limits.minTurnRadius * (180.0 / kPi);
    double heading = state.headingDegrees + turnDegrees;
    heading -= 360.0 * std::floor((heading + 180.0) / 360.0); // [-180, 180)
    const glm::dvec2 along = headingDirection(state.headingDegrees + 0.5 * turnDegrees);
    return VehicleState{.position = state.position + along * (speed * dt), .headingDegrees = heading, .speed = speed};
}

glm::dvec2 headingDirection(double degrees) {
    double turns = degrees / 360.0;
    turns -= std::floor(turns);        // [0, 1)
    double quarterBack = turns - 0.25; // sin(2 pi u) = cos(2 pi (u - 1/4))
    if (quarterBack < 0.0) quarterBack += 1.0;
    return {exactCosTwoPi(turns), exactCosTwoPi(quarterBack)};
}

double headingDegreesOf(glm::dvec2 d) {
    require(std::isfinite(d.x) && std::isfinite(d.y) && (d.x != 0.0 || d.y != 0.0),
            "a heading needs a finite, non-zero direction");
    double radians;
    if (std::abs(d.y) <= std::abs(d.x)) {
        radians = exactAtan(d.y / d.x);
        if (d.x < 0.0) radians += d.y >= 0.0 ? kPi : -kPi;
    } else {
        radians = (d.y > 0.0 ? 0.5 * kPi : -0.5 * kPi) - exactAtan(d.x / d.y);
    }
    return radians * (180.0 / kPi);
}

} // namespace sward
