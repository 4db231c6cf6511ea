// Image files: EXR written by sward read back with OpenCV.
#include "common/half_float.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include "test_files.h"

#include <opencv2/imgcodecs.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace sward;

TEST(ExrFiles, ReadBackWithOpenCvToExactlyTheWrittenValues) {
    const std::string dir = sward::test::tempDir().string();
    const uint32_t w = 7, h = 5;
    std::vector<float> depth(w * h);
    std::vector<uint16_t> rgba(w * h * 4);
    for (uint32_t i = 0; i < w * h; ++i) {
        depth[i] = i == 3 ? INFINITY : 0.001f + float(i) * 1.37f;
        for (uint32_t c = 0; c < 4; ++c) rgba[i * 4 + c] = uint16_t(0x3000 + i * 37 + c * 5); // assorted halves
    }
    writeExrDepth(dir + "/d.exr", w, h, depth);
    writeExrRgbaHalf(dir + "/c.exr", w, h, rgba);
    cv::Mat d = cv::imread(dir + "/d.exr", cv::IMREAD_UNCHANGED);
    cv::Mat c = cv::imread(dir + "/c.exr", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(d.type(), CV_32FC1);
    ASSERT_EQ(c.type(), CV_32FC4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            uint32_t i = y * w + x;
            EXPECT_EQ(d.at<float>(int(y), int(x)), depth[i]);
            cv::Vec4f px = c.at<cv::Vec4f>(int(y), int(x));
            EXPECT_EQ(px[2], halfBitsToFloat(rgba[i * 4 + 0])); // R (OpenCV orders BGRA)
            EXPECT_EQ(px[1], halfBitsToFloat(rgba[i * 4 + 1])); // G
            EXPECT_EQ(px[0], halfBitsToFloat(rgba[i * 4 + 2])); // B
            EXPECT_EQ(px[3], halfBitsToFloat(rgba[i * 4 + 3])); // A
        }
    EXPECT_FALSE(std::filesystem::exists(dir + "/d.exr.tmp"));
}

TEST(ExrFiles, FloatSamplesReadBackThroughLoadImageExactly) {
    const std::string dir = sward::test::tempDir().string();
    for (uint32_t channels : {1u, 3u, 4u}) {
        const uint32_t w = 3, h = 2;
        std::vector<float> samples(w * h * channels);
        for (size_t i = 0; i < samples.size(); ++i) samples[i] = float(i) * 0.75f - 2.0f;
        const std::string path = dir + "/f" + std::to_string(channels) + ".exr";
        writeExr(path, w, h, channels, samples);
        const ImageData image = loadImage(path);
        EXPECT_EQ(image.channels, channels);
        EXPECT_EQ(image.samples, samples) << channels << " channel(s)";
        EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    }
}
