// A deliberately independent PFM reader for tests that read sward's files as a user's tools would: "Pf",
// width height, negative scale = little endian, bottom row first (Middlebury 2014 / ETH3D).
#pragma once

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <fstream>
#include <string>

namespace sward::test {

inline cv::Mat readPfm(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::string magic;
    int width = 0, height = 0;
    double scale = 0;
    file >> magic >> width >> height >> scale;
    file.get(); // the single whitespace byte before the data
    EXPECT_EQ(magic, "Pf");
    EXPECT_LT(scale, 0.0) << "expected little-endian data";
    cv::Mat image(height, width, CV_32F);
    for (int row = height - 1; row >= 0; --row) file.read(reinterpret_cast<char*>(image.ptr<float>(row)), width * 4);
    EXPECT_TRUE(file.good()) << path;
    return image;
}

} // namespace sward::test
