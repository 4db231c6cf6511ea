// Closed-loop driving from a program (the Python module's Simulator.drive, render/session.h): a kinematic bicycle
// model stepped once per simulation tick. Throttle, steer and brake in, the vehicle's pose out. Plain + - * /, sqrt,
// floor and common/exact_math.h only (no libm sin, cos or atan2), so a driven episode places the vehicle with the same
// bits on every machine and C library.
#pragma once

#include <glm/glm.hpp>

namespace sward {

// One tick's controls, each checked by checkVehicleCommand.
struct VehicleCommand {
    double throttle = 0.0; // -1 (full reverse) .. 1 (full ahead): acceleration throttle * VehicleLimits::acceleration
    double steer = 0.0;    // -1 (full right) .. 1 (full left): path curvature steer / VehicleLimits::minTurnRadius
    double brake = 0.0;    // 0 .. 1: deceleration towards standstill brake * VehicleLimits::braking
};

// The model's limits (docs/python.md, "Drive and record"): those of a small field rover such as examples/assets/
// rover.gltf (0.7 m wheel base; a bicycle of that wheel base turns at 1.5 m with its front wheel at 25 degrees).
struct VehicleLimits {
    double maxSpeed = 3.0;        // m/s ahead
    double maxReverseSpeed = 1.5; // m/s backwards
    double acceleration = 2.0;    // m/s^2 at full throttle
    double braking = 6.0;         // m/s^2 at full brake
    double drag = 0.5;            // m/s^2 towards standstill while the throttle is 0 (rolling resistance)
    double minTurnRadius = 1.5;   // metres at full steer
};

struct VehicleState {
    glm::dvec2 position{0.0};    // world xy of the vehicle's origin (a scene object's: its model's origin)
    double headingDegrees = 0.0; // direction of travel, from +x towards +y, in [-180, 180)
    double speed = 0.0;          // m/s along the heading; negative when reversing
};

// Throws sward::Error naming the first control that is not finite or out of its range.
void checkVehicleCommand(const VehicleCommand& command);

// The state `dt` seconds (> 0) later: the speed changes by the throttle's acceleration and the brake's (and, without
// throttle, the drag's) deceleration, never through standstill by braking, within [-maxReverseSpeed, maxSpeed]; the
// heading turns by speed * dt * steer / minTurnRadius radians; the position moves speed * dt along the mean of the two
// headings (the chord of the arc, to second order).
VehicleState stepVehicle(const VehicleState& state, const VehicleCommand& command, const VehicleLimits& limits,
                         double dt);

// The unit xy direction of a heading in degrees (from +x towards +y), by exactCosTwoPi.
glm::dvec2 headingDirection(double degrees);
// The heading in degrees, [-180, 180], of a non-zero xy direction (within 1e-12 degrees of atan2's).
double headingDegreesOf(glm::dvec2 direction);

} // namespace sward
