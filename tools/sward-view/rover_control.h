// RoverControl: the rover the user drives from the keyboard (arrow keys). Its pose is integrated per simulation
// tick (so tracks do not depend on frame rate); its wheels collide with the grass through the simulation's
// external colliders, and it is drawn as the scene's rover model (or, without one, as an outline box).
#pragma once

#include "interaction/colliders.h"
#include "scene/vehicles.h"
#include "world/camera.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

struct GLFWwindow;

namespace sward {

class FlyCamera;
class Ground;
class ObjectRenderer;
class Overlay;

// The rover's pose and speed.
struct Rover {
    glm::dvec2 position{0.0};
    double heading = 0.0; // radians from +x towards +y
    double speed = 0.0;   // m/s, negative = reversing
    glm::dvec2 direction() const { return {std::cos(heading), std::sin(heading)}; }
    // One tick of `dt` seconds: throttle and steer are -1, 0 or 1; autodrive != 0 holds that speed (m/s).
    void step(double throttle, double steer, double autodrive, double dt);
};

class RoverControl {
public:
    // The vehicle (wheel base, track, wheel radius) the rover is built like.
    void setVehicle(const VehicleParams& vehicle) { vehicle_ = vehicle; }
    // Places the rover where `camera` looks (on the ground within 300 m), else 6 m ahead, heading the way it
    // looks; from then on it is active (collides and is drawn).
    void spawn(const FlyCamera& camera, const Ground& terrain);
    void deactivate() { active_ = false; }
    bool active() const { return active_; }
    glm::dvec2 position() const { return rover_.position; }

    // One simulation tick: arrow keys of `window` drive it when `keyboard` (else no throttle, no steering).
    void step(GLFWwindow* window, bool keyboard, double autodrive, double dt);
    // The wheel colliders on `terrain`, numbered as vehicle `index` (wheelColliders' ids).
    std::vector<Collider> wheelColliders(const Ground& terrain, uint32_t index) const;
    // True for the ids wheelColliders(terrain, index) gives.
    static bool isWheel(const Collider& c, uint32_t index);
    // Behind and above the rover, looking just over it.
    Camera followCamera(const Ground& terrain, double fovYDegrees, uint32_t width, uint32_t height) const;
    // Shows the rover as model `model` of `objects` (hidden while inactive), or without a model as an outline
    // box in `overlay`.
    void show(ObjectRenderer* objects, std::optional<size_t> model, const Ground& terrain, Overlay& overlay) const;

private:
    void outline(const Ground& terrain, Overlay& overlay) const;

    Rover rover_;
    VehicleParams vehicle_;
    bool active_ = false; // the rover exists: it collides and is drawn (from the first F on)
};

} // namespace sward
