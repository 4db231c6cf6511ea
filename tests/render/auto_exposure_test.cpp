// Auto-exposure in a run (render/auto_exposure.h): the frames a run renders to prime each frame's window, a step from
// the sky to the ground followed within the time constant, and sward-render's files and recorded exposures the same
// whole, in shards and resumed.
#include "render/auto_exposure.h"

#include "gpu_test.h"
#include "render/session.h"
#include "scene/scene_input.h"
#include "scene/sensor_model.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>

using namespace sward;

namespace {

AutoExposureParams params(double tau) {
    return {.enabled = true, .targetGrey = 0.18, .timeConstantSeconds = tau};
}

// A linear half RGBA image of `pixels` grey pixels of half bits `grey`.
std::vector<uint16_t> greyImage(uint16_t grey, size_t pixels = 4) {
    std::vector<uint16_t> image;
    for (size_t p = 0; p < pixels; ++p) image.insert(image.end(), {grey, grey, grey, 0x3c00});
    return image;
}

} // namespace

TEST(AutoExposure, ARunRendersTheWindowBeforeEachFrameToWriteOnce) {
    const AutoExposure exposure(params(0.3), 0.1); // W = ceil(5 * 0.3 / 0.1) = 15
    ASSERT_EQ(exposure.window(), 15u);
    EXPECT_EQ(exposure.framesToRender({20, 21}),
              (std::vector<uint32_t>{5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21}));
    const std::vector<uint32_t> gap = exposure.framesToRender({3, 40});
    EXPECT_EQ(gap.front(), 0u);
    EXPECT_EQ(gap.size(), 4u + 16u); // 0..3, then 25..40: the frames between the windows are not rendered
    EXPECT_EQ(gap[4], 25u);
    EXPECT_EQ(AutoExposure(params(0.0), 0.1).framesToRender({7, 9}), (std::vector<uint32_t>{7, 9}));
}

TEST(AutoExposure, AFrameMeteredAfterItsWindowGetsTheWholeRunsFactorBitwise) {
    AutoExposure whole(params(0.2), 0.1), primed(params(0.2), 0.1); // W = 10
    const uint16_t greys[] = {0x3000, 0x3400, 0x3800, 0x2c00};      // 0.125, 0.25, 0.5, 0.0625
    std::vector<FrameImages::Exposure> run;
    for (uint32_t frame = 0; frame < 30; ++frame) run.push_back(whole.meter(frame, greyImage(greys[frame * 7 % 4])));
    for (uint32_t frame = 19; frame < 30; ++frame) { // a shard from frame 29: its window 19..28 primed
        const FrameImages::Exposure e = primed.meter(frame, greyImage(greys[frame * 7 % 4]));
        EXPECT_EQ(e.meter, run[frame].meter);
        if (frame == 29) {
            EXPECT_EQ(e.factor, run[frame].factor);
        }
    }
    AutoExposure unprimed(params(0.2), 0.1);
    EXPECT_NE(unprimed.meter(29, greyImage(greys[29 * 7 % 4])).factor, run[29].factor); // the test can fail
}

TEST(AutoExposure, TheSensorKeyIsReadAndWrittenBackOnlyWhenGiven) {
    const SensorParams without =
        parseSensor(nlohmann::json::parse(R"({"exposure": 2})"), "scene.json", "camera.sensor");
    EXPECT_FALSE(without.autoExposure.enabled);
    EXPECT_FALSE(sensorToJson(without).contains("auto_exposure")); // frames.jsonl as before the key existed
    const SensorParams with =
        parseSensor(nlohmann::json::parse(R"({"auto_exposure": {"target_grey": 0.25, "time_constant_s": 1}})"),
                    "scene.json", "camera.sensor");
    EXPECT_TRUE(with.autoExposure.enabled);
    EXPECT_EQ(sensorToJson(with)["auto_exposure"]["target_grey"], 0.25);
    EXPECT_EQ(parseSensor(sensorToJson(with), "scene.json", "camera.sensor").autoExposure.timeConstantSeconds, 1.0);
}

// A Session (the same frames as sward-render) looking at the sky, then at the ground from frame kStep on: the
// exposure, in stops, has gone at least 1 - 1/e of the way one time constant after the step, not at once, and ends
// where the ground's meter puts it, the exposed image's mean at the target grey.
TEST(AutoExposure, ASkyToGroundStepIsFollowedWithinTheTimeConstant) {
    constexpr double kTau = 0.2, kStep = 0.05;
    constexpr uint32_t kWindow = 20, kStepFrame = kWindow + 1; // W = 5 tau / dt; the step after a whole window
    Scene scene = loadSceneInput(
        {.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
         .overrides = nlohmann::json({{"render.resolution", {64, 48}},
                                      {"render.samples", 1},
                                      {"camera.baseline", 0},
                                      {"sequence.time_step", kStep},
                                      {"sequence.frames", 50},
                                      {"camera.sensor", {{"auto_exposure", {{"time_constant_s", kTau}}}}}})
                          .dump()});
    Session session(std::move(scene), SessionOptions{.validation = true});
    const glm::dvec3 eye(50.0, 50.0, 8.0);
    session.setCamera(eye, glm::dvec3(56.0, 50.0, 100.0), std::nullopt); // the sky
    std::vector<double> ev, mean;
    for (uint32_t frame = 0; frame <= kStepFrame + kWindow; ++frame) {
        if (frame == kStepFrame) session.setCamera(eye, glm::dvec3(53.0, 50.0, -20.0), std::nullopt); // the ground
        const SessionFrame f = session.render();
        ASSERT_TRUE(f.images.autoExposure.has_value());
        ev.push_back(std::log2(f.images.autoExposure->factor));
        mean.push_back(meterLuminance(f.images.rgbaHalf));
    }
    EXPECT_EQ(ev[0], ev[kStepFrame - 1]); // the sky's meter alone: steady from the first frame
    const double total = ev.back() - ev[kStepFrame - 1];
    EXPECT_GT(std::abs(total), 1.0) << "the ground is not darker than the sky by a stop: no step to follow";
    auto followed = [&](uint32_t frame) { return (ev[frame] - ev[kStepFrame - 1]) / total; };
    EXPECT_LT(followed(kStepFrame), 0.5);                                   // not at once
    EXPECT_GE(followed(kStepFrame + uint32_t(kTau / kStep)), 1.0 - 0.3679); // 1 - 1/e after tau
    for (uint32_t frame = kStepFrame; frame + 1 < ev.size(); ++frame)
        EXPECT_GE(followed(frame + 1), followed(frame)) << frame; // monotonic
    RecordProperty("stops", std::to_string(total));
    RecordProperty("followed_at_step", std::to_string(followed(kStepFrame)));
    RecordProperty("followed_after_tau", std::to_string(followed(kStepFrame + uint32_t(kTau / kStep))));
    RecordProperty("exposed_mean", std::to_string(mean.back()));
    EXPECT_NEAR(mean.back(), 0.18, 0.18 * 0.1); // the exposed ground at the target grey (the wind moves plants)
    EXPECT_EQ(session.device().validationMessageCount(), 0u);
}

// The exposure machinery changes the colour by the factor alone: a factor of exactly 1 (min_ev = max_ev = 0) gives
// bitwise the frames of a scene without the key (noise on, three frames, the Session stepping over one), and the
// free factor does not.
TEST(AutoExposure, AFactorOfOneLeavesEveryImageBitwise) {
    auto session = [](const nlohmann::json& autoExposure) {
        nlohmann::json sensor = {{"electrons_per_unit", 500}, {"read_noise", 2}};
        if (!autoExposure.is_null()) sensor["auto_exposure"] = autoExposure;
        return std::make_unique<Session>(
            loadSceneInput(
                {.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                 .overrides =
                     nlohmann::json({{"render.resolution", {64, 48}}, {"render.samples", 1}, {"camera.sensor", sensor}})
                         .dump()}),
            SessionOptions{.validation = true});
    };
    auto frames = [](Session& s) {
        std::vector<SessionFrame> out;
        out.push_back(s.render());
        s.step(1);
        out.push_back(s.render());
        return out;
    };
    const auto without = session(nullptr), one = session({{"min_ev", 0}, {"max_ev", 0}}),
               free = session(nlohmann::json::object());
    const std::vector<SessionFrame> a = frames(*without), b = frames(*one), c = frames(*free);
    for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_FALSE(a[k].images.autoExposure.has_value());
        ASSERT_TRUE(b[k].images.autoExposure.has_value());
        EXPECT_EQ(b[k].images.autoExposure->factor, 1.0);
        EXPECT_EQ(a[k].images.rgbaHalf, b[k].images.rgbaHalf) << k;
        EXPECT_EQ(a[k].images.rightRgbaHalf, b[k].images.rightRgbaHalf) << k;
        EXPECT_EQ(a[k].images.depth, b[k].images.depth) << k;
        EXPECT_EQ(a[k].images.labels, b[k].images.labels) << k;
        EXPECT_NE(a[k].images.rgbaHalf, c[k].images.rgbaHalf) << k; // the test can fail
        EXPECT_EQ(a[k].images.depth, c[k].images.depth) << k;       // the truth never changes
    }
}

// sward-render with auto-exposure (W = 2 at 0.2 s frames, tau 0.06 s) and a moving camera: two shards and a run
// resumed after lost files write the whole run's files, auto_exposure/ among them: the second shard and the resumed
// run render the frames before their first for the meters alone.
TEST(AutoExposureDataset, ShardsAndResumedRunsWriteTheWholeRunsFilesAndExposures) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 2.0}};
    scene["camera"]["sensor"] = {
        {"auto_exposure", {{"time_constant_s", 0.06}}}, {"electrons_per_unit", 500}, {"read_noise", 2}};
    const std::string dir = sward::test::tempDir("auto-exposure-shards"), path = dir + "/scene.json";
    std::ofstream(path) << scene.dump();
    std::string err;
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/whole", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --shard " + shard, err), 0) << err;
    auto compare = [&] { return sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts"); };
    EXPECT_GT(compare(), 6u * 18);
    std::set<std::string> factors; // the camera's motion changes the meter: not one factor for every frame
    for (uint32_t frame = 0; frame < 6; ++frame) {
        const nlohmann::json record = nlohmann::json::parse(
            sward::test::readFile(dir + "/whole/auto_exposure/00000" + std::to_string(frame) + ".json"));
        EXPECT_EQ(record["frame"], frame);
        factors.insert(record["factor"].dump());
    }
    EXPECT_GT(factors.size(), 3u);
    std::filesystem::remove(dir + "/parts/left/000004.exr");
    std::filesystem::remove(dir + "/parts/auto_exposure/000005.json");
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts", err), 0) << err;
    compare();
}
