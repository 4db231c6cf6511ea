// FlyCamera: a free camera for the viewer, moved by WASD (+ Q/E down/up) and turned by the mouse. World Z up;
// yaw is the heading in the ground plane measured from +x towards +y, pitch is up from the horizon.
#pragma once

#include "world/camera.h"

#include <glm/glm.hpp>

namespace sward {

struct FlyInput {
    glm::dvec3 move{0.0};   // local: x right, y forward, z up; each -1..1
    glm::dvec2 turn{0.0};   // mouse delta in pixels: x right, y down
    bool fast = false;      // shift held: 4x speed
};

class FlyCamera {
public:
    FlyCamera() = default;
    // Starts at `position` looking at `target`.
    FlyCamera(glm::dvec3 position, glm::dvec3 target);

    void update(const FlyInput& input, double dt);
    // Points the camera from `position` at `target` (follow mode).
    void lookAt(glm::dvec3 position, glm::dvec3 target);
    // Multiplies the speed by 1.25 per wheel notch (up: faster), kept within 0.25 .. 500 m/s.
    void scaleSpeed(double notches);

    Camera camera(double fovYDegrees, uint32_t width, uint32_t height) const;
    glm::dvec3 position() const { return position_; }
    glm::dvec3 forward() const;
    double speed() const { return speed_; }
    // Keeps the camera at least `clearance` metres above `groundHeight` (no flying through hills).
    void clampAbove(double groundHeight, double clearance);

private:
    glm::dvec3 position_{0.0};
    double yaw_ = 0.0, pitch_ = 0.0; // radians
    double speed_ = 8.0;             // metres per second
};

} // namespace sward
