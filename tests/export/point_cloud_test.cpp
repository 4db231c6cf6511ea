// Point clouds: one point per pixel with depth, back-projected through the pixel centre.
#include "export/point_cloud.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace sward;

TEST(PointCloud, PixelsWithDepthBecomePointsThroughTheirCentres) {
    FrameTruth truth{.width = 2, .height = 2};
    truth.depth = {2.0f, std::numeric_limits<float>::infinity(), 4.0f, 1.0f};
    truth.semantic = {1, 0, 3, 8};
    truth.instance = {0, 0, 7, 16000000};
    truth.rgb = {1, 2, 3, 0, 0, 0, 4, 5, 6, 7, 8, 9};
    const ExportCamera camera{.fx = 2.0, .fy = 2.0, .cx = 0.5, .cy = 0.5, .width = 2, .height = 2};
    glm::dmat4 pose(1.0);
    pose[3] = glm::dvec4(10.0, 20.0, 30.0, 1.0); // a translation only
    const std::string ply = pointCloudPly(truth, camera, pose, "test");
    const size_t end = ply.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(ply.find("element vertex 3\n"), std::string::npos); // the sky pixel has no point
    const char* data = ply.data() + end + 11;
    const size_t stride = 3 * 8 + 3 + 1 + 4;
    ASSERT_EQ(ply.size() - (end + 11), 3 * stride);
    // Third point: pixel (1, 1), depth 1: x = (1 - 0.5) * 1 / 2 = 0.25.
    double xyz[3];
    std::memcpy(xyz, data + 2 * stride, 24);
    EXPECT_EQ(xyz[0], 10.25);
    EXPECT_EQ(xyz[1], 20.25);
    EXPECT_EQ(xyz[2], 31.0);
    EXPECT_EQ(uint8_t(data[2 * stride + 24]), 7);
    EXPECT_EQ(uint8_t(data[2 * stride + 27]), 8);
    uint32_t instance = 0;
    std::memcpy(&instance, data + 2 * stride + 28, 4);
    EXPECT_EQ(instance, 16000000u);
}
