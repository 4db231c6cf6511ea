// The truth images of a frame as the dataset and the Python module store them.
#include "dataset/frame_truth.h"

#include "shared/gpu_layout.h"

#include <gtest/gtest.h>

#include <limits>

using namespace sward;

TEST(FrameTruth, LabelsSplitIntoClassAndInstanceAndDepthIntoDisparity) {
    FrameImages images{.width = 2, .height = 1};
    images.labels = {(3u << gpu::kInstanceBits) | 12345u, (8u << gpu::kInstanceBits) | 16000000u};
    images.depth = {2.0f, std::numeric_limits<float>::infinity()};
    const FrameTruth stereo = frameTruth(images, 100.0, 0.1);
    EXPECT_EQ(stereo.semantic, (std::vector<uint8_t>{3, 8}));
    EXPECT_EQ(stereo.instance, (std::vector<float>{12345.0f, 16000000.0f}));
    EXPECT_EQ(stereo.disparity, (std::vector<float>{5.0f, 0.0f})); // f * B / Z; nothing hit: 0
    EXPECT_TRUE(frameTruth(images, 100.0, 0.0).disparity.empty());  // mono: no disparity
}
