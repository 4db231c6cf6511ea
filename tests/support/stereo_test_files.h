// Helpers for the stereo tests: a fresh temporary folder per test and a tiny synthetic stereo dataset laid out like
// sward-render's output (docs/dataset contract), whose true disparity is known exactly.
#pragma once

#include "common/hash.h"
#include "dataset/naming.h"
#include "io/disparity_files.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sward::test {

inline std::string tempDir(const std::string& suffix = "") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    auto dir = std::filesystem::temp_directory_path() /
               ("sward_stereo_tests_" + std::string(info->test_suite_name()) + "_" + info->name() + suffix);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

inline std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

struct SyntheticDataset {
    uint32_t width = 192, height = 128;
    uint32_t frames = 2;
    int disparity = 8;     // every textured pixel's true disparity, in pixels
    uint32_t skyRows = 16; // the top rows have no ground truth (sky)
    uint64_t seed = 1;
};

// Writes calib.txt, disparity/NNNNNN.{pfm,png}, preview/ and preview_right/ PNGs and semantic/ PNGs into `dir`.
// The left view is blocky random colour texture T(x, y); the right view is T(x + d, y), so x_right = x_left - d.
// Semantic classes: left half ground (1), right half grass (3); sky rows 0.
inline void writeSyntheticDataset(const std::string& dir, const SyntheticDataset& s) {
    namespace fs = std::filesystem;
    for (const char* sub : {kDisparityFolder, kPreviewFolder, kPreviewRightFolder, kSemanticFolder})
        fs::create_directories(dir + "/" + sub);
    StereoCalib calib;
    const double f = 100.0;
    calib.cam0 = {f, 0, s.width / 2.0, 0, f, s.height / 2.0, 0, 0, 1};
    calib.cam1 = calib.cam0;
    calib.baselineMm = 100.0;
    calib.width = s.width;
    calib.height = s.height;
    calib.ndisp = 32;
    calib.vmin = 0;
    calib.vmax = 16;
    writeMiddleburyCalib(dir + "/" + kCalibFile, calib);
    for (uint32_t frame = 0; frame < s.frames; ++frame) {
        // 2x2-pixel texture cells: texture with some spatial correlation matches more robustly than per-pixel noise.
        auto texel = [&](int x, int y, int c) {
            return uint8_t(hashKey({s.seed, frame, uint64_t(x / 2 + 4096), uint64_t(y / 2), uint64_t(c)}) >> 56);
        };
        cv::Mat left(int(s.height), int(s.width), CV_8UC3), right(int(s.height), int(s.width), CV_8UC3);
        cv::Mat semantic(int(s.height), int(s.width), CV_8UC1);
        std::vector<float> truth(size_t(s.width) * s.height);
        for (int y = 0; y < int(s.height); ++y)
            for (int x = 0; x < int(s.width); ++x) {
                for (int c = 0; c < 3; ++c) {
                    left.at<cv::Vec3b>(y, x)[c] = texel(x, y, c);
                    right.at<cv::Vec3b>(y, x)[c] = texel(x + s.disparity, y, c);
                }
                const bool sky = y < int(s.skyRows);
                truth[size_t(y) * s.width + x] = sky ? 0.0f : float(s.disparity);
                // gpu::kSemanticSky, kSemanticGround, kSemanticVegetation + 1 (dataset/naming.h's table)
                semantic.at<uint8_t>(y, x) = sky ? 0 : (x < int(s.width / 2) ? 1 : 3);
            }
        auto path = [&](const char* folder, const char* extension) {
            return dir + "/" + frameFile(folder, frame, extension);
        };
        writePfm(path(kDisparityFolder, ".pfm"), s.width, s.height, truth);
        writeKittiPng(path(kDisparityFolder, ".png"), s.width, s.height, truth);
        cv::imwrite(path(kPreviewFolder, ".png"), left);
        cv::imwrite(path(kPreviewRightFolder, ".png"), right);
        cv::imwrite(path(kSemanticFolder, ".png"), semantic);
    }
}

} // namespace sward::test
