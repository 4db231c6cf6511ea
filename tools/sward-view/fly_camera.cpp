#include "fly_camera.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {
constexpr double kMaxPitch = 1.55;      // just short of straight up/down, where "up" would be undefined
constexpr double kRadiansPerPixel = 0.003;
} // namespace

FlyCamera::FlyCamera(glm::dvec3 position, glm::dvec3 target) { lookAt(position, target); }

void FlyCamera::lookAt(glm::dvec3 position, glm::dvec3 target) {
    position_ = position;
    glm::dvec3 d = target - position;
    if (glm::length(d) < 1e-9) return;
    yaw_ = std::atan2(d.y, d.x);
    pitch_ = std::clamp(std::atan2(d.z, std::hypot(d.x, d.y)), -kMaxPitch, kMaxPitch);
}

glm::dvec3 FlyCamera::forward() const {
    return {std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_)};
}

void FlyCamera::update(const FlyInput& input, double dt) {
    yaw_ -= input.turn.x * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ - input.turn.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    glm::dvec3 right(std::sin(yaw_), -std::cos(yaw_), 0.0);
    // Forward follows the view (pitch included), so looking down and pressing W descends: what a flight does.
    glm::dvec3 velocity = forward() * input.move.y + right * input.move.x + glm::dvec3(0, 0, 1) * input.move.z;
    position_ += velocity * (speed_ * (input.fast ? 4.0 : 1.0) * dt);
}

void FlyCamera::scaleSpeed(double notches) { speed_ = std::clamp(speed_ * std::pow(1.25, notches), 0.25, 500.0); }

void FlyCamera::clampAbove(double groundHeight, double clearance) {
    position_.z = std::max(position_.z, groundHeight + clearance);
}

Camera FlyCamera::camera(double fovYDegrees, uint32_t width, uint32_t height) const {
    return Camera::lookAt(position_, position_ + forward(), glm::dvec3(0, 0, 1), fovYDegrees, width, height);
}

} // namespace sward
