// A Bayer sensor through sward-render (scene/sensor_bayer.h): raw/ holds the single-channel mosaic of the colour the
// EXR holds, two runs write the same bytes, and "bayer": null writes the files of a sensor without the key.
#include "gpu_test.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

// The test scene at 64x48 (mono) with a noisy camera.
nlohmann::json bayerScene(const nlohmann::json& extraSensorKeys) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["camera"]["baseline"] = 0.0; // a single camera
    scene["camera"]["sensor"] = {{"electrons_per_unit", 2000}, {"read_noise", 2}, {"full_well", 2000}};
    scene["camera"]["sensor"].update(extraSensorKeys);
    return scene;
}

} // namespace

// raw/000000.png is one 16-bit channel: each pixel the DN of its RGGB photosite's channel of the left EXR (within
// 1 DN: the EXR holds the float signal rounded to half), and frames.jsonl names the pattern. A second run writes the
// very same files.
TEST(SensorBayerDataset, RawIsTheSingleChannelMosaicAndRunsRepeat) {
    const std::string dir = sward::test::tempDir("sensor-bayer");
    const std::string path =
        sward::test::writeSceneFile(dir, "scene", bayerScene({{"bayer", "RGGB"}, {"bit_depth", 12}}).dump());
    std::string err;
    for (const char* out : {"/first", "/second"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + out + " --frames 0:1", err), 0) << err;
    EXPECT_GT(sward::test::expectSameRunFiles(dir + "/first", dir + "/second"), 5u);
    const cv::Mat raw = cv::imread(dir + "/first/raw/000000.png", cv::IMREAD_UNCHANGED);
    const cv::Mat exr = cv::imread(dir + "/first/left/000000.exr", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(raw.type(), CV_16UC1);
    ASSERT_EQ(raw.size(), cv::Size(64, 48));
    ASSERT_EQ(exr.size(), raw.size());
    int worst = 0;
    for (int y = 0; y < raw.rows; ++y)
        for (int x = 0; x < raw.cols; ++x) {
            const int rgb = (y % 2) + (x % 2);                                // RGGB: 0 R, 1 G, 2 B
            const double v = exr.ptr<float>(y)[x * exr.channels() + 2 - rgb]; // OpenCV's B, G, R order
            const int expected = int(std::floor(std::clamp(v, 0.0, 1.0) * 4095.0 + 0.5));
            worst = std::max(worst, std::abs(int(raw.at<uint16_t>(y, x)) - expected));
        }
    EXPECT_LE(worst, 1);
    const std::string records = sward::test::readFile(dir + "/first/frames.jsonl");
    EXPECT_NE(records.find("\"bayer\":\"RGGB\""), std::string::npos) << records;
}

// "bayer": null is the three-channel sensor: every file (frames.jsonl too) as without the key.
TEST(SensorBayerDataset, NullBayerWritesTheThreeChannelSensorsFiles) {
    const std::string dir = sward::test::tempDir("sensor-bayer-null");
    std::string err;
    for (const auto& [name, keys] : {std::pair{"none", nlohmann::json{{"bit_depth", 8}}},
                                     std::pair{"null", nlohmann::json{{"bit_depth", 8}, {"bayer", nullptr}}}})
        ASSERT_EQ(sward::test::runSwardRender(sward::test::writeSceneFile(dir, name, bayerScene(keys).dump()) +
                                                  " --out " + dir + "/" + name + " --frames 0:1",
                                              err),
                  0)
            << err;
    EXPECT_GT(sward::test::expectSameRunFiles(dir + "/none", dir + "/null"), 5u);
    EXPECT_EQ(cv::imread(dir + "/null/raw/000000.png", cv::IMREAD_UNCHANGED).type(), CV_8UC3);
}
