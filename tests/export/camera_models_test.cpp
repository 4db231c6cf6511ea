// Camera models: COLMAP's quaternions.
#include "export/camera_models.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace sward;

namespace {

// Rotation matrix of a unit quaternion (w, x, y, z), written out independently of the code under test.
glm::dmat3 rotationOf(double w, double x, double y, double z) {
    glm::dmat3 r;
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    r[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    r[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    return r;
}

} // namespace

TEST(CameraModels, QuaternionsReproduceTheirRotationsInEveryBranch) {
    const glm::dvec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, glm::normalize(glm::dvec3(1, -2, 0.5))};
    for (const glm::dvec3& axis : axes)
        for (double angle : {0.0, 0.3, 1.7, 3.0, 3.14159, -2.5}) {
            const glm::dmat3 r(glm::rotate(glm::dmat4(1.0), angle, axis));
            const glm::dvec4 q = rotationQuaternion(r);
            EXPECT_GE(q.x, 0.0);
            EXPECT_NEAR(glm::dot(q, q), 1.0, 1e-12);
            const glm::dmat3 back = rotationOf(q.x, q.y, q.z, q.w);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[c][k], r[c][k], 1e-12) << angle;
        }
}
