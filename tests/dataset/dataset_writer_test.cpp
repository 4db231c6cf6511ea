// The dataset writer: which files a frame has, and that writeFrame writes exactly those, named by dataset/naming.h.
#include "dataset/dataset_writer.h"

#include "dataset/naming.h"
#include "shared/gpu_layout.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace sward;

namespace {

std::string freshDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    auto dir = std::filesystem::temp_directory_path() / ("sward_dataset_tests_" + std::string(info->name()));
    std::filesystem::remove_all(dir);
    return dir.string();
}

FrameImages tinyFrame(bool stereo) {
    FrameImages images;
    images.width = 2;
    images.height = 1;
    images.rgbaHalf.assign(8, 0x3c00); // 1.0
    images.depth = {2.0f, INFINITY};
    images.labels = {gpu::kSemanticGround << gpu::kInstanceBits, gpu::kSemanticSky << gpu::kInstanceBits};
    if (stereo) images.rightRgbaHalf = images.rgbaHalf;
    return images;
}

} // namespace

TEST(DatasetWriter, FrameFilesAreNamedByTheNamingTable) {
    const DatasetWriter mono("unused", false), stereo("unused", true);
    const std::vector<std::string> monoFiles = mono.frameFiles(7);
    EXPECT_EQ(monoFiles.size(), 5u);
    EXPECT_EQ(monoFiles[0], frameFile(kLeftFolder, 7, ".exr"));
    const std::vector<std::string> stereoFiles = stereo.frameFiles(7);
    EXPECT_EQ(stereoFiles.size(), 10u);
    EXPECT_NE(std::find(stereoFiles.begin(), stereoFiles.end(), "disparity/000007.pfm"), stereoFiles.end());
    EXPECT_EQ(mono.datasetFiles(), std::vector<std::string>{kFrameLogFile});
    EXPECT_EQ(stereo.datasetFiles(), (std::vector<std::string>{kFrameLogFile, kCalibFile}));
}

TEST(DatasetWriter, WriteFrameWritesEveryListedFileAndTheClassBytes) {
    const std::string dir = freshDir();
    DatasetWriter writer(dir, true);
    writer.begin({{"test", 1}}, false);
    EXPECT_FALSE(writer.frameComplete(3));
    Camera left;
    left.fx = 100;
    writer.writeFrame(3, tinyFrame(true), left, 0.1);
    EXPECT_TRUE(writer.frameComplete(3));
    const cv::Mat semantic = cv::imread(dir + "/" + frameFile(kSemanticFolder, 3, ".png"), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(semantic.type(), CV_8UC1);
    EXPECT_EQ(semantic.at<uint8_t>(0, 0), gpu::kSemanticGround);
    EXPECT_EQ(semantic.at<uint8_t>(0, 1), gpu::kSemanticSky);
}
