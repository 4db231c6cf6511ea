// Camera model: rays and projection.
#include "world/camera.h"

#include <gtest/gtest.h>

using namespace sward;

TEST(Camera, ProjectsItsOwnRaysBackToThePixel) {
    Camera camera = Camera::lookAt({1, 2, 3}, {10, 20, 1}, {0, 0, 1}, 50.0, 320, 240);
    glm::dvec3 p = camera.position + 7.5 * camera.ray(100.5, 30.5);
    glm::dvec3 q = camera.project(p);
    EXPECT_NEAR(q.x, 100.5, 1e-9);
    EXPECT_NEAR(q.y, 30.5, 1e-9);
    EXPECT_NEAR(q.z, 7.5, 1e-9);
    // Clip space: x/w, y/w map to the same pixel; depth = near / z (reversed Z).
    glm::dvec4 clip = camera.viewProjection() * glm::dvec4(p, 1.0);
    EXPECT_NEAR((clip.x / clip.w + 1.0) * 0.5 * 320, 100.5, 1e-6);
    EXPECT_NEAR((clip.y / clip.w + 1.0) * 0.5 * 240, 30.5, 1e-6);
    EXPECT_NEAR(clip.z / clip.w, camera.nearPlane / 7.5, 1e-12);
}
