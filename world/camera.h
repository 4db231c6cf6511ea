// Pinhole camera in OpenCV conventions, shared by rendering, ground truth and dataset output.
//
// Camera axes: x right, y down, z forward (optical axis). Pixel (u, v) has its top-left corner at the
// origin, so the centre of pixel (i, j) is (i + 0.5, j + 0.5). Planar depth is the camera-space z in metres.
// World: right-handed, Z up, metres.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace sward {

struct Camera {
    glm::dvec3 position{0.0};
    glm::dmat3 worldFromCamera{1.0};               // columns: camera x (right), y (down), z (forward) in world axes
    double fx = 1.0, fy = 1.0, cx = 0.5, cy = 0.5; // intrinsics in pixels
    uint32_t width = 1, height = 1;
    double nearPlane = 0.05; // metres; the far plane is at infinity (reversed Z)

    // Camera at `position` looking at `target` with world up `up`; square pixels, centred principal point.
    static Camera lookAt(glm::dvec3 position, glm::dvec3 target, glm::dvec3 up, double fovYDegrees, uint32_t width,
                         uint32_t height);

    // World -> camera (OpenCV axes) rigid transform.
    glm::dmat4 view() const;
    // Camera -> Vulkan clip space: reversed Z (depth = near / z), infinite far plane, y down like pixels.
    glm::dmat4 projection() const;
    glm::dmat4 viewProjection() const { return projection() * view(); }
    // Direction through pixel coordinate (u, v), scaled so that its camera-space z is 1: the point at
    // planar depth d is position + d * ray(u, v).
    glm::dvec3 ray(double u, double v) const;
    // Pixel coordinate and planar depth of a world point.
    glm::dvec3 project(glm::dvec3 world) const;
    // World-space frustum planes: near, left, right, top, bottom (the far plane is at infinity). xyz is the
    // unit inward normal, w the offset: a point p is inside when dot(xyz, p) + w >= 0 for all five.
    std::array<glm::vec4, 5> frustumPlanes() const;
};

// Planes of the union of a rectified stereo pair's frusta (`right` = `left` moved along left's +x axis, same
// orientation and intrinsics): the two cameras' top and bottom planes coincide, so the union is bounded by
// left's near, left and top/bottom planes and right's right plane.
std::array<glm::vec4, 5> stereoFrustumPlanes(const Camera& left, const Camera& right);

} // namespace sward
