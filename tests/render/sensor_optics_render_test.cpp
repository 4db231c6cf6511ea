// The lens (scene/sensor_optics.h) in sward-render's datasets: it changes the colour of both views and nothing else,
// each view is the optics pass of the ideal colour with that view's own truth depth, bit for bit, and a lens with no
// effect leaves every file as it was.
#include "gpu_test.h"

#include "scene/sensor_model.h"
#include "scene/sensor_optics.h"

#include "common/half_float.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>

using sward::test::readFile;
using sward::test::runSwardRender;
using sward::test::tempDir;

namespace {

const std::string kScene = SWARD_TEST_DATA_DIR "/dataset_scene.json"; // 160 x 120, stereo

// Renders frame 0 of the test scene with `sensor` as camera.sensor into `dir`/out.
std::string renderWithSensor(const std::string& dir, const nlohmann::json& sensor) {
    nlohmann::json scene = nlohmann::json::parse(readFile(kScene));
    scene["camera"]["sensor"] = sensor;
    std::ofstream(dir + "/scene.json") << scene.dump();
    std::string err;
    EXPECT_EQ(runSwardRender(dir + "/scene.json --out " + dir + "/out --frames 0:1", err), 0) << err;
    return dir + "/out";
}

nlohmann::json firstRecord(const std::string& out) {
    const std::string lines = readFile(out + "/frames.jsonl");
    return nlohmann::json::parse(lines.substr(0, lines.find('\n')));
}

cv::Mat readExr(const std::string& path) {
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(image.empty()) << "cannot read " << path;
    return image;
}

} // namespace

TEST(SensorOpticsRender, LensBlursEachViewByItsOwnDepthAndLeavesTheTruthAlone) {
    const nlohmann::json lens = {{"aperture_f", 1.0},
                                 {"focus_distance_m", 0.1},
                                 {"pixel_size_um", 50.0},
                                 {"mtf_sigma_px", 0.5},
                                 {"chromatic_aberration_px", 0.5}};
    const std::string plainDir = tempDir("optics-plain"), lensDir = tempDir("optics-lens"),
                      zeroDir = tempDir("optics-zero");
    const std::string plain = renderWithSensor(plainDir, nlohmann::json::object()); // on, no lens: the ideal colour
    const std::string through = renderWithSensor(lensDir, lens);
    const std::string zero = renderWithSensor(zeroDir, {{"aperture_f", 0}, {"mtf_sigma_px", 0}, {"pixel_size_um", 5}});

    for (const char* file : {"/depth/000000.exr", "/depth_right/000000.exr", "/disparity/000000.pfm",
                             "/disparity_right/000000.pfm", "/semantic/000000.png", "/instance/000000.exr",
                             "/normal/000000.exr", "/normal_right/000000.exr", "/occlusion/000000.png"})
        EXPECT_EQ(readFile(plain + file), readFile(through + file)) << file << ": ground truth stays the pinhole's";
    for (const char* file : {"/left/000000.exr", "/right/000000.exr", "/preview/000000.png", "/frames.jsonl"})
        EXPECT_EQ(readFile(plain + file), readFile(zero + file)) << file << ": a lens without effect changes nothing";

    const nlohmann::json record = firstRecord(through);
    EXPECT_EQ(record.at("sensor").at("aperture_f"), 1.0);
    EXPECT_FALSE(firstRecord(plain).at("sensor").contains("aperture_f"));

    // The CPU pass on the ideal colour with the view's truth depth reproduces the render's colour bit for bit.
    const nlohmann::json& k = record.at("intrinsics"); // OpenCV's pixel centres; camera.h's are half a pixel on
    const sward::Intrinsics camera{
        k.at("fx"),    k.at("fy"),    k.at("cx").get<double>() + 0.5, k.at("cy").get<double>() + 0.5,
        k.at("width"), k.at("height")};
    const sward::SensorOptics optics(sward::parseSensor(lens, "test", "camera.sensor"), camera);
    for (const auto& [view, depthFolder] : {std::pair{"left", "depth"}, std::pair{"right", "depth_right"}}) {
        const std::string frame = std::string("/") + view + "/000000.exr";
        const cv::Mat ideal = readExr(plain + frame), blurred = readExr(through + frame);
        const cv::Mat depth = readExr(plain + "/" + depthFolder + "/000000.exr");
        ASSERT_EQ(ideal.type(), CV_32FC4);
        ASSERT_EQ(depth.type(), CV_32FC1);
        std::vector<uint16_t> half(size_t(ideal.total()) * 4);
        for (size_t p = 0; p < ideal.total(); ++p)
            for (int c = 0; c < 4; ++c) // OpenCV's BGRA to RGBA
                half[p * 4 + size_t(c)] = sward::floatToHalfBits(ideal.at<cv::Vec4f>(int(p))[c == 3 ? 3 : 2 - c]);
        optics.applyHalf({depth.ptr<float>(), depth.total()}, half);
        size_t changed = 0, mismatched = 0;
        for (size_t p = 0; p < ideal.total(); ++p)
            for (int c = 0; c < 3; ++c) {
                const float got = blurred.at<cv::Vec4f>(int(p))[2 - c];
                changed += got != ideal.at<cv::Vec4f>(int(p))[2 - c];
                mismatched += sward::floatToHalfBits(got) != half[p * 4 + size_t(c)];
            }
        EXPECT_EQ(mismatched, 0u) << view;
        EXPECT_GT(changed, ideal.total()) << view << ": the lens blurs most of the image";
    }
}
