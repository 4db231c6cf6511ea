#include "world/camera.h"

#include "common/error.h"

#include <cmath>
#include <numbers>

namespace sward {

Camera Camera::lookAt(glm::dvec3 position, glm::dvec3 target, glm::dvec3 up, double fovYDegrees, uint32_t width,
                      uint32_t height) {
    glm::dvec3 forward = target - position;
    require(glm::length(forward) > 1e-9, "camera target must differ from the camera position");
    require(fovYDegrees > 0.1 && fovYDegrees < 179.0, "camera field of view must be between 0.1 and 179 degrees");
    require(width > 0 && height > 0, "camera resolution must be positive");
    forward = glm::normalize(forward);
    glm::dvec3 right = glm::cross(forward, up);
    require(glm::length(right) > 1e-9, "camera must not look straight along its up vector");
    right = glm::normalize(right);
    glm::dvec3 down = glm::cross(forward, right);
    Camera camera;
    camera.position = position;
    camera.worldFromCamera = glm::dmat3(right, down, forward);
    camera.width = width;
    camera.height = height;
    camera.fy = 0.5 * height / std::tan(0.5 * fovYDegrees * std::numbers::pi / 180.0);
    camera.fx = camera.fy;
    camera.cx = 0.5 * width;
    camera.cy = 0.5 * height;
    return camera;
}

glm::dmat4 Camera::view() const {
    glm::dmat3 cameraFromWorld = glm::transpose(worldFromCamera);
    glm::dmat4 view(cameraFromWorld);
    view[3] = glm::dvec4(-(cameraFromWorld * position), 1.0);
    return view;
}

glm::dmat4 Camera::projection() const {
    // clip = (2fx/w x + (2cx/w - 1) z,  2fy/h y + (2cy/h - 1) z,  near,  z), so NDC x, y in [-1, 1] map to
    // pixels [0, w] x [0, h] and depth = near / z (1 at the near plane, 0 at infinity).
    glm::dmat4 p(0.0);
    p[0][0] = 2.0 * fx / width;
    p[1][1] = 2.0 * fy / height;
    p[2][0] = 2.0 * cx / width - 1.0;
    p[2][1] = 2.0 * cy / height - 1.0;
    p[2][3] = 1.0;
    p[3][2] = nearPlane;
    return p;
}

glm::dvec3 Camera::ray(double u, double v) const {
    return worldFromCamera * glm::dvec3((u - cx) / fx, (v - cy) / fy, 1.0);
}

glm::dvec3 Camera::project(glm::dvec3 world) const {
    glm::dvec3 c = glm::transpose(worldFromCamera) * (world - position);
    return {fx * c.x / c.z + cx, fy * c.y / c.z + cy, c.z};
}

} // namespace sward

namespace sward {

std::array<glm::vec4, 5> Camera::frustumPlanes() const {
    // Gribb & Hartmann: combinations of the rows of the clip matrix. Reversed Z: near is depth <= 1, w - z >= 0.
    glm::dmat4 m = glm::transpose(viewProjection());
    glm::dvec4 planes[5] = {m[3] - m[2], m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1]};
    std::array<glm::vec4, 5> out;
    for (int i = 0; i < 5; ++i) out[size_t(i)] = glm::vec4(planes[i] / glm::length(glm::dvec3(planes[i])));
    return out;
}

std::array<glm::vec4, 5> stereoFrustumPlanes(const Camera& left, const Camera& right) {
    std::array<glm::vec4, 5> planes = left.frustumPlanes();
    planes[2] = right.frustumPlanes()[2];
    return planes;
}

} // namespace sward
