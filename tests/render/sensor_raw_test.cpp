// The camera's digital output through sward-render (scene/sensor_raw.h): raw/ and raw_right/ hold the DN of the
// colour the EXRs hold, the other files are those of a run without it, and shards / resumed runs write the same bytes.
#include "gpu_test.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

namespace {

// The test scene at 64x48 (stereo) with a camera: shot and read noise, a full well and a black level.
nlohmann::json rawScene(const nlohmann::json& extraSensorKeys) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 2.0}};
    scene["camera"]["sensor"] = {
        {"electrons_per_unit", 2000}, {"read_noise", 2}, {"full_well", 1875}, {"black_level", 0.0625}};
    scene["camera"]["sensor"].update(extraSensorKeys);
    return scene;
}

} // namespace

// raw/000000.png holds round(left EXR / white * 4095) within 1 DN everywhere (white = black level + full well / epu =
// 0.0625 + 0.9375 = 1): the ADC reads the float signal, the EXR holds it rounded to half, whose 11 significant bits
// put a value below 1 at most 2^-12 off, under one 12-bit step, so the two roundings differ by at most 1 DN (with a
// white level that is no power of two, by up to 2). The same for the right view.
TEST(SensorRawDataset, TwelveBitRawIsTheLinearColourQuantised) {
    const std::string dir = sward::test::tempDir("sensor-raw-12");
    std::string err;
    const std::string path = sward::test::writeSceneFile(dir, "scene", rawScene({{"bit_depth", 12}}).dump());
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/out --frames 0:1", err), 0) << err;
    const double white = 0.0625 + 1875.0 / 2000.0;
    for (const auto& [rawFolder, colourFolder] : {std::pair{"raw", "left"}, std::pair{"raw_right", "right"}}) {
        const cv::Mat raw = cv::imread(dir + "/out/" + rawFolder + "/000000.png", cv::IMREAD_UNCHANGED);
        const cv::Mat exr = cv::imread(dir + "/out/" + colourFolder + "/000000.exr", cv::IMREAD_UNCHANGED);
        ASSERT_EQ(raw.type(), CV_16UC3) << rawFolder; // 16-bit PNG, the DN in the low bits
        ASSERT_EQ(exr.depth(), CV_32F);
        ASSERT_EQ(raw.size(), cv::Size(64, 48));
        ASSERT_EQ(exr.size(), raw.size());
        int worst = 0, clipped = 0, pedestal = 0;
        std::set<int> levels;
        for (int y = 0; y < raw.rows; ++y)
            for (int x = 0; x < raw.cols; ++x)
                for (int c = 0; c < 3; ++c) { // both B, G, R in OpenCV's order
                    const double v = exr.ptr<float>(y)[x * exr.channels() + c];
                    const int expected = int(std::floor(std::clamp(v / white, 0.0, 1.0) * 4095.0 + 0.5));
                    const int dn = raw.at<cv::Vec3w>(y, x)[c];
                    worst = std::max(worst, std::abs(dn - expected));
                    clipped += dn == 4095;
                    pedestal += dn >= 250; // 0.0625 * 4095 = 255.9: the black level under the noise
                    levels.insert(dn);
                }
        EXPECT_LE(worst, 1) << rawFolder;
        EXPECT_GT(levels.size(), 200u) << rawFolder << ": a real image, not a constant";
        EXPECT_GT(clipped, 0) << rawFolder << ": the sky passes the well"; // the clip is reached
        EXPECT_GT(pedestal, 64 * 48 * 3 * 9 / 10) << rawFolder;
    }
}

// bit_depth 0 writes the very files of a sensor without the key; bit_depth 8 adds raw/ and raw_right/ (8-bit PNG) and
// changes no other file but frames.jsonl's sensor record (which gains the key).
TEST(SensorRawDataset, TheDigitalOutputChangesNoOtherFile) {
    const std::string dir = sward::test::tempDir("sensor-raw-other");
    std::string err;
    for (const auto& [name, keys] :
         {std::pair{"none", nlohmann::json::object()}, std::pair{"zero", nlohmann::json{{"bit_depth", 0}}},
          std::pair{"eight", nlohmann::json{{"bit_depth", 8}}}})
        ASSERT_EQ(sward::test::runSwardRender(sward::test::writeSceneFile(dir, name, rawScene(keys).dump()) +
                                                  " --out " + dir + "/" + name + " --frames 0:1",
                                              err),
                  0)
            << err;
    const size_t withoutKey = sward::test::expectSameRunFiles(dir + "/none", dir + "/zero"); // frames.jsonl among them
    EXPECT_EQ(withoutKey, 20u);
    EXPECT_FALSE(std::filesystem::exists(dir + "/zero/raw"));
    // Every other file of the run without the key (all but frames.jsonl, skipped) is compared, bytewise equal.
    EXPECT_EQ(sward::test::expectSameRunFiles(dir + "/eight", dir + "/none",
                                              {"frames.jsonl", "raw/000000.png", "raw_right/000000.png"}),
              withoutKey - 1);
    const cv::Mat raw = cv::imread(dir + "/eight/raw/000000.png", cv::IMREAD_UNCHANGED);
    EXPECT_EQ(raw.type(), CV_8UC3);
    EXPECT_TRUE(std::filesystem::exists(dir + "/eight/raw_right/000000.png"));
    const std::string records = sward::test::readFile(dir + "/eight/frames.jsonl");
    EXPECT_NE(records.find("\"bit_depth\":8"), std::string::npos) << records;
}

// Two shards, and a run resumed after a lost raw file, write the very raw files (and all others) of one whole run.
TEST(SensorRawDataset, ShardsAndResumedRunsWriteTheWholeRunsFiles) {
    const std::string dir = sward::test::tempDir("sensor-raw-shards");
    const std::string path = sward::test::writeSceneFile(dir, "scene", rawScene({{"bit_depth", 12}}).dump());
    std::string err;
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/whole --frames 0:3", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3 --shard " + shard, err), 0)
            << err;
    // 3 frames of 19 files (raw/ and raw_right/ among them), frames.jsonl, classes.json and calib.txt.
    EXPECT_EQ(sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts"), 3u * 19 + 3);
    EXPECT_TRUE(std::filesystem::exists(dir + "/parts/raw/000002.png"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/parts/raw_right/000001.png"));
    std::filesystem::remove(dir + "/parts/raw/000001.png");
    std::filesystem::remove(dir + "/parts/raw_right/000002.png");
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3", err), 0) << err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/parts/raw/000001.png"));
    sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts");
}
