#include "rover_control.h"

#include "fly_camera.h"
#include "overlay.h"
#include "render/object_renderer.h"
#include "world/ground.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace sward {

void Rover::step(double throttle, double steer, double autodrive, double dt) {
    if (autodrive != 0.0) speed = autodrive;
    else {
        double target = throttle > 0 ? 4.0 : throttle < 0 ? -2.0 : 0.0;
        double accel = throttle != 0 ? 3.0 : 5.0; // braking is quicker than accelerating
        speed += std::clamp(target - speed, -accel * dt, accel * dt);
    }
    heading += steer * 1.2 * dt * (speed < 0 ? -1.0 : 1.0) * std::min(std::abs(speed) / 1.0, 1.0);
    position += direction() * (speed * dt);
}

void RoverControl::spawn(const FlyCamera& camera, const Ground& terrain) {
    glm::dvec3 eye = camera.position(), forward = camera.forward();
    glm::dvec2 flat = glm::length(glm::dvec2(forward)) > 1e-6 ? glm::normalize(glm::dvec2(forward)) : glm::dvec2(1, 0);
    std::optional<double> hit = terrain.raycast(eye, forward, 300.0);
    glm::dvec2 at = hit ? glm::dvec2(eye + forward * *hit) : glm::dvec2(eye) + flat * 6.0;
    rover_ = Rover{at, std::atan2(flat.y, flat.x), 0.0};
    active_ = true;
}

void RoverControl::step(GLFWwindow* window, bool keyboard, double autodrive, double dt) {
    auto down = [&](int key) { return keyboard && glfwGetKey(window, key) == GLFW_PRESS; };
    double throttle = (down(GLFW_KEY_UP) ? 1.0 : 0.0) - (down(GLFW_KEY_DOWN) ? 1.0 : 0.0);
    double steer = (down(GLFW_KEY_LEFT) ? 1.0 : 0.0) - (down(GLFW_KEY_RIGHT) ? 1.0 : 0.0);
    rover_.step(throttle, steer, autodrive, dt);
}

std::vector<Collider> RoverControl::wheelColliders(const Ground& terrain, uint32_t index) const {
    return sward::wheelColliders(vehicle_, vehicleWheelsAt(vehicle_, terrain, rover_.position, rover_.direction()),
                                 index);
}

bool RoverControl::isWheel(const Collider& c, uint32_t index) {
    const uint32_t first = 1000 * (index + 1);
    return c.id >= first && c.id < first + 4;
}

Camera RoverControl::followCamera(const Ground& terrain, double fovYDegrees, uint32_t width,
                                  uint32_t height) const {
    glm::dvec2 back = glm::dvec2(rover_.position) - rover_.direction() * 6.0;
    glm::dvec3 eye(back, terrain.height(glm::vec2(back)) + 3.5);
    glm::dvec3 target(rover_.position, terrain.height(glm::vec2(rover_.position)) + 0.4);
    return Camera::lookAt(eye, target, glm::dvec3(0, 0, 1), fovYDegrees, width, height);
}

void RoverControl::show(ObjectRenderer* objects, std::optional<size_t> model, const Ground& terrain,
                        Overlay& overlay) const {
    if (objects && model) {
        objects->setVisible(*model, active_);
        if (active_) objects->place(*model, rover_.position, rover_.heading);
    } else if (active_) {
        outline(terrain, overlay);
    }
}

void RoverControl::outline(const Ground& terrain, Overlay& overlay) const {
    // No rover model installed: a box over its wheels, so it can be seen while it drives.
    glm::dvec2 f = rover_.direction(), l(-f.y, f.x);
    float z = terrain.height(glm::vec2(rover_.position)) + 2.0f * vehicle_.wheelRadius;
    glm::vec3 color(3.0f, 3.0f, 3.0f);
    glm::vec2 corners[4];
    for (int i = 0; i < 4; ++i)
        corners[i] = glm::vec2(rover_.position + f * ((i < 2 ? 0.5 : -0.5) * (vehicle_.wheelBase + 0.2)) +
                               l * ((i == 0 || i == 3 ? 0.5 : -0.5) * vehicle_.trackWidth));
    for (int i = 0; i < 4; ++i) {
        overlay.line(glm::vec3(corners[i], z), glm::vec3(corners[(i + 1) % 4], z), color);
        overlay.line(glm::vec3(corners[i], z + 0.25f), glm::vec3(corners[(i + 1) % 4], z + 0.25f), color);
        overlay.line(glm::vec3(corners[i], z), glm::vec3(corners[i], z + 0.25f), color);
    }
}

} // namespace sward
