// The dataset writer: which files a frame has, and that writeFrame writes exactly those, named by dataset/naming.h;
// one writer per folder (shards together) and no write or removal through a link.
#include "dataset/dataset_writer.h"
#include "test_files.h"

#include "common/error.h"
#include "dataset/naming.h"
#include "shared/gpu_layout.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

using namespace sward;
using sward::test::errorOf;

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
    images.normals = {0.6f, -0.48f, -0.64f, 0.0f, 0.0f, 0.0f}; // a unit normal facing the camera, then sky
    if (stereo) {
        images.rightRgbaHalf = images.rgbaHalf;
        images.rightDepth = images.depth;
        images.rightLabels = images.labels;
        images.rightNormals = images.normals;
    }
    return images;
}

} // namespace

TEST(DatasetWriter, FrameFilesAreNamedByTheNamingTable) {
    const DatasetWriter mono("unused", false), stereo("unused", true);
    const std::vector<std::string> monoFiles = mono.frameFiles(7);
    EXPECT_EQ(monoFiles.size(), 6u);
    EXPECT_EQ(monoFiles[0], frameFile(kLeftFolder, 7, ".exr"));
    const std::vector<std::string> stereoFiles = stereo.frameFiles(7);
    EXPECT_EQ(stereoFiles.size(), 17u);
    for (const char* file :
         {"normal/000007.exr", "normal_right/000007.exr", "disparity/000007.pfm", "disparity_right/000007.pfm",
          "depth_right/000007.exr", "occlusion/000007.png", "occlusion_right/000007.png"})
        EXPECT_NE(std::find(stereoFiles.begin(), stereoFiles.end(), file), stereoFiles.end()) << file;
    EXPECT_EQ(mono.datasetFiles(), (std::vector<std::string>{kFrameLogFile, kSceneCopyFile, kClassesFile}));
    EXPECT_EQ(stereo.datasetFiles(),
              (std::vector<std::string>{kFrameLogFile, kSceneCopyFile, kClassesFile, kCalibFile}));
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

TEST(DatasetWriter, NormalFileReadsBackInOpenCvAsTheExactFloatNormals) {
    const std::string dir = freshDir();
    DatasetWriter writer(dir, false);
    writer.begin({{"test", 1}}, false);
    const FrameImages images = tinyFrame(false);
    writer.writeFrame(0, images, Camera{}, 0.0);
    // OpenCV reads EXR channels R, G, B as a 3-channel float image in its own B, G, R order.
    const cv::Mat normal = cv::imread(dir + "/" + frameFile(kNormalFolder, 0, ".exr"), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(normal.type(), CV_32FC3);
    for (int x = 0; x < 2; ++x)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(normal.at<cv::Vec3f>(0, x)[2 - c], images.normals[size_t(3 * x + c)]) << x << " " << c;
}

namespace {

const nlohmann::json kPrint = {{"resolution", "2x1"}, {"samples", 1}};

std::vector<std::string> listing(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        names.push_back(std::filesystem::relative(entry.path(), dir).string());
    std::sort(names.begin(), names.end());
    return names;
}

void touch(const std::string& path) {
    std::ofstream(path) << "user data";
}

} // namespace

TEST(DatasetWriter, AnotherFingerprintIsRefusedBeforeAnythingIsWritten) {
    const std::string dir = freshDir();
    DatasetWriter first(dir, false);
    first.begin(kPrint, false);
    first.writeFrame(0, tinyFrame(false), Camera{}, 0.1);
    const std::vector<std::string> before = listing(dir);
    nlohmann::json other = kPrint;
    other["resolution"] = "4x2";
    DatasetWriter second(dir, false);
    EXPECT_EQ(errorOf([&] { second.check(other, false, 0); }),
              "'" + dir +
                  "' was rendered with --resolution 2x1, this run asks for --resolution 4x2; use --overwrite "
                  "to start over or choose another --out");
    EXPECT_EQ(listing(dir), before);
    EXPECT_EQ(errorOf([&] { second.check(kPrint, false, 0); }), "") << "the same fingerprint resumes";
    EXPECT_EQ(errorOf([&] { second.check(other, true, 0); }), "") << "--overwrite";
}

TEST(DatasetWriter, DatasetFilesWithoutAFingerprintAreRefused) {
    const std::string dir = freshDir();
    std::filesystem::create_directories(dir + "/left");
    touch(dir + "/left/000000.exr");
    EXPECT_NE(errorOf([&] { DatasetWriter(dir, false).check(kPrint, false, 0); }).find("no dataset.json"),
              std::string::npos);
}

TEST(DatasetWriter, OverwriteRemovesSwardFilesOnlyAndKeepsForeignOnes) {
    const std::string dir = freshDir();
    DatasetWriter old(dir, true);
    old.begin(kPrint, false);
    old.writeFrame(0, tinyFrame(true), Camera{}, 0.1);
    old.writeManifest("manifest.shard-0-of-2.json", nlohmann::json::object(), {});
    touch(dir + "/notes.tmp");
    touch(dir + "/left/mine.txt");
    DatasetWriter fresh(dir, false); // mono now: the stereo folders go too
    fresh.begin({{"resolution", "8x8"}}, true);
    EXPECT_EQ(listing(dir), (std::vector<std::string>{"dataset.json", "depth", "instance", "left", "left/mine.txt",
                                                      "normal", "notes.tmp", "preview", "semantic"}));
}

TEST(DatasetWriter, BeginKeepsTheUsersTmpFilesAndRemovesDeadSwardTemporaries) {
    const std::string dir = freshDir();
    std::filesystem::create_directories(dir + "/left");
    touch(dir + "/keep.tmp");
    touch(dir + "/left/000000.exr.tmp");
    touch(dir + "/left/.000000.exr.sward-999999999.tmp"); // no such process
    DatasetWriter writer(dir, false);
    writer.begin(kPrint, false);
    const std::vector<std::string> names = listing(dir);
    EXPECT_NE(std::find(names.begin(), names.end(), "keep.tmp"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "left/000000.exr.tmp"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "left/.000000.exr.sward-999999999.tmp"), names.end());
}

TEST(DatasetWriter, DiscardCreatedLeavesTheFolderAsFound) {
    const std::string dir = freshDir();
    DatasetWriter earlier(dir, true);
    earlier.begin(kPrint, false);
    earlier.writeFrame(0, tinyFrame(true), Camera{}, 0.1);
    const std::vector<std::string> before = listing(dir);
    DatasetWriter failing(dir, true);
    failing.begin(kPrint, false);
    failing.writeFrame(1, tinyFrame(true), Camera{}, 0.1);
    failing.writeFrameLog({{{"frame", 0}}});
    failing.discardCreated();
    EXPECT_EQ(listing(dir), before);

    const std::string missing = dir + "/new/nested";
    DatasetWriter fromNothing(missing, false);
    fromNothing.begin(kPrint, false);
    fromNothing.writeFrame(0, tinyFrame(false), Camera{}, 0.1);
    fromNothing.discardCreated();
    EXPECT_FALSE(std::filesystem::exists(dir + "/new")) << "folders it created go too";
}

TEST(DatasetWriter, CheckRefusesAFolderWithoutRoomOrUnderAFile) {
    const std::string dir = freshDir();
    std::filesystem::create_directories(dir);
    const std::string space =
        errorOf([&] { DatasetWriter(dir + "/out", true).check(kPrint, false, ~uint64_t(0) / 2); });
    EXPECT_NE(space.find("not enough space in '" + dir + "/out' for one frame"), std::string::npos) << space;
    touch(dir + "/file");
    const std::string underFile = errorOf([&] { DatasetWriter(dir + "/file/out", true).check(kPrint, false, 0); });
    EXPECT_NE(underFile.find("cannot create output folder '" + dir + "/file/out'"), std::string::npos) << underFile;
    EXPECT_EQ(listing(dir), std::vector<std::string>{"file"});
}

TEST(DatasetWriter, FrameBoundCoversTheFilesWritten) {
    const std::string dir = freshDir();
    DatasetWriter writer(dir, true);
    writer.begin(kPrint, false);
    FrameImages images = tinyFrame(true);
    writer.writeFrame(0, images, Camera{}, 0.1);
    uint64_t written = 0;
    for (const std::string& file : writer.frameFiles(0)) written += std::filesystem::file_size(dir + "/" + file);
    EXPECT_GE(writer.frameBytesUpperBound(images.width, images.height), written);
}

TEST(DatasetWriter, ConcurrentShardsWithAnotherFingerprintAreRefusedAtBegin) {
    const std::string dir = freshDir();
    DatasetWriter first(dir, false);
    first.begin(kPrint, false);
    DatasetWriter second(dir, false);
    EXPECT_NE(errorOf([&] {
                  second.begin({{"resolution", "9x9"}}, false);
              }).find("--resolution 9x9"),
              std::string::npos);
}

TEST(DatasetWriter, ALinkAmongTheDatasetsNamesIsRefusedAndOverwriteNeverRemovesThroughIt) {
    const std::string dir = freshDir(), elsewhere = dir + "-elsewhere";
    std::filesystem::remove_all(elsewhere);
    {
        DatasetWriter first(dir, false);
        first.begin(kPrint, false);
        first.writeFrame(0, tinyFrame(false), Camera{}, 0.1);
    }
    std::filesystem::rename(dir + "/left", elsewhere); // left/ is now a link to a folder outside the dataset
    std::filesystem::create_directory_symlink(elsewhere, dir + "/left");
    const std::vector<std::string> outside = listing(elsewhere);
    DatasetWriter second(dir, false);
    for (bool overwrite : {false, true})
        EXPECT_EQ(errorOf([&] { second.check(kPrint, overwrite, 0); }),
                  "'" + dir +
                      "/left' is a symbolic link: sward never writes through links in an output folder; "
                      "remove it or choose another --out");
    EXPECT_NE(errorOf([&] { second.begin(kPrint, true); }).find("is a symbolic link"), std::string::npos)
        << "begin() checks again";
    EXPECT_EQ(listing(elsewhere), outside);
}

// The checks above run when a render starts; a link swapped in for left/ while it runs is refused at the next write
// (the writer writes below a handle on its folder, common/atomic_file.h's OutputRoot) and nothing reaches its target.
TEST(DatasetWriter, ALinkSwappedInMidRunIsRefusedAtTheNextWrite) {
    const std::string dir = freshDir(), elsewhere = dir + "-elsewhere";
    std::filesystem::remove_all(elsewhere);
    std::filesystem::create_directories(elsewhere);
    DatasetWriter writer(dir, false);
    writer.begin(kPrint, false);
    writer.writeFrame(0, tinyFrame(false), Camera{}, 0.1);
    std::filesystem::remove_all(dir + "/left");
    std::filesystem::create_directory_symlink(elsewhere, dir + "/left");
    EXPECT_NE(errorOf([&] { writer.writeFrame(1, tinyFrame(false), Camera{}, 0.2); }).find("symbolic link"),
              std::string::npos);
    EXPECT_TRUE(listing(elsewhere).empty());
}

TEST(DatasetWriter, ASecondWriterIsRefusedNamingTheFirstAndAFailedRunLeavesNoLockFile) {
    const std::string dir = freshDir();
    DatasetWriter first(dir, false);
    first.lock(false);
    first.begin(kPrint, false);
    const std::string held =
        "'" + dir + "' is being written by another sward process (pid " + std::to_string(::getpid()) + ")";
    EXPECT_EQ(errorOf([&] { DatasetWriter(dir, false).check(kPrint, false, 0); }).rfind(held, 0), 0u);
    EXPECT_EQ(errorOf([&] { DatasetWriter(dir, false).lock(true); }).rfind(held, 0), 0u) << "a shard beside it";
    first.discardCreated();
    EXPECT_FALSE(std::filesystem::exists(dir)) << "the run's folder, lock file included, is gone";
}

TEST(DatasetWriter, ShardsShareTheFolderAndTheLastLeavesNoLockFile) {
    const std::string dir = freshDir();
    {
        DatasetWriter shard0(dir, false), shard1(dir, false);
        shard0.lock(true);
        shard1.lock(true);
        EXPECT_NE(errorOf([&] { DatasetWriter(dir, false).lock(false); }), "") << "a whole-range run beside shards";
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + kOutputLockFile));
}
