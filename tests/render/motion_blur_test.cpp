// Exposure time and motion blur (render/motion_blur.h): the colour image of a frame with a shutter is the mean of
// instantaneous renders at the sub-frame times, a point light streaks by the motion the pinhole model predicts, the
// ground truth stays the instant's bit for bit, and the sensor reads the integrated light out.
#include "gpu_test.h"

#include "common/half_float.h"
#include "render/motion_blur.h"
#include "render/scene_gpu.h"
#include "render/scene_renderer.h"
#include "render/sequence_frame.h"
#include "scene/scene_input.h"
#include "scene/scene_resources.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

using namespace sward;

namespace {

using MotionBlurTest = sward::test::GpuTest;

constexpr uint32_t kWidth = 96, kHeight = 64;

// The GPU test scene at 96 x 64, one sample, its camera driving 2 m/s along a path (wind on), with `overrides`
// (dotted keys).
SceneResources testScene(const nlohmann::json& overrides, bool vegetation = true) {
    nlohmann::json all = {{"render.resolution", {kWidth, kHeight}},
                          {"render.samples", 1},
                          {"camera.path", {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 2.0}}}};
    all.update(overrides);
    return buildSceneResources(
        loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json", .overrides = all.dump()}),
        vegetation);
}

double maxAbsDifference(const std::vector<uint16_t>& a, const std::vector<uint16_t>& b) {
    EXPECT_EQ(a.size(), b.size());
    double largest = 0.0;
    for (size_t k = 0; k < std::min(a.size(), b.size()); ++k)
        largest = std::max(largest, std::abs(double(halfBitsToFloat(a[k])) - double(halfBitsToFloat(b[k]))));
    return largest;
}

bool bitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The mean of full (colour and truth) instantaneous renders of the scene's rig at `times`, written out here: a float
// sum in time order, one division, one rounding to half.
struct Mean {
    std::vector<uint16_t> left, right;
};
Mean meanOfInstants(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, const std::vector<double>& times,
                    uint32_t frame) {
    std::vector<float> left, right;
    for (double t : times) {
        const RigCameras rig = sequenceRigAt(r, kWidth, kHeight, t);
        const FrameImages instant = target.render(*gpu.renderer, rig.left, t, frame, {}, &rig.right);
        left.resize(instant.rgbaHalf.size(), 0.0f);
        right.resize(instant.rightRgbaHalf.size(), 0.0f);
        for (size_t k = 0; k < left.size(); ++k) left[k] += halfBitsToFloat(instant.rgbaHalf[k]);
        for (size_t k = 0; k < right.size(); ++k) right[k] += halfBitsToFloat(instant.rightRgbaHalf[k]);
    }
    Mean mean;
    for (float sum : left) mean.left.push_back(floatToHalfBits(sum / float(times.size())));
    for (float sum : right) mean.right.push_back(floatToHalfBits(sum / float(times.size())));
    return mean;
}

} // namespace

TEST(MotionBlur, SubFrameTimesAreCentredOnTheFrame) {
    const std::vector<double> times = exposureTimes(2.0, 0.08, 4);
    ASSERT_EQ(times.size(), 4u);
    EXPECT_DOUBLE_EQ(times[0], 1.97);
    EXPECT_DOUBLE_EQ(times[1], 1.99);
    EXPECT_DOUBLE_EQ(times[2], 2.01);
    EXPECT_DOUBLE_EQ(times[3], 2.03);
    EXPECT_EQ(exposureTimes(2.0, 0.08, 3)[1], 2.0); // an odd count samples the instant itself
}

TEST(MotionBlur, AutoSamplesFollowTheCameraMotion) {
    const Camera start = Camera::lookAt({0, 0, 2}, {0, 10, 2}, {0, 0, 1}, 60.0, 160, 120);
    // A pan by 0.1 rad about the camera's own vertical axis: a point at infinity on the optical axis moves
    // fx tan(0.1) pixels, the image's corners further.
    Camera panned = start;
    const double a = 0.1;
    panned.worldFromCamera =
        start.worldFromCamera * glm::dmat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a));
    const double centre = start.fx * std::tan(a);
    const double motion = cameraMotionPixels(start, panned, 1.0);
    EXPECT_GT(motion, centre);
    EXPECT_LT(motion, 2.0 * centre);
    EXPECT_EQ(cameraMotionPixels(start, start, 1.0), 0.0);
    // A sideways step of 1 cm: the parallax of the nearest depth, fx * 0.01 / 1 m.
    Camera moved = start;
    moved.position.x += 0.01;
    EXPECT_NEAR(cameraMotionPixels(start, moved, 1.0), start.fx * 0.01, 1e-9);
    EXPECT_NEAR(cameraMotionPixels(start, moved, 2.0), start.fx * 0.005, 1e-9);
    EXPECT_EQ(autoMotionSamples(0.0), kMinAutoMotionSamples);
    EXPECT_EQ(autoMotionSamples(7.2), 8u);
    EXPECT_EQ(autoMotionSamples(1000.0), kMaxAutoMotionSamples);
    EXPECT_EQ(autoMotionSamples(INFINITY), kMaxAutoMotionSamples);
    EXPECT_EQ(autoMotionSamples(NAN), kMaxAutoMotionSamples);
}

// The motion_blur output of a sideways step and of a pan, against the pinhole's figures.
TEST(MotionBlur, BlurLengthIsTheParallaxOfTheExactDepth) {
    const Camera centre = Camera::lookAt({0, 0, 2}, {0, 10, 2}, {0, 0, 1}, 60.0, 64, 48);
    Camera start = centre, end = centre;
    start.position -= 0.05 * centre.worldFromCamera[0]; // 10 cm sideways over the exposure
    end.position += 0.05 * centre.worldFromCamera[0];
    std::vector<float> depth(64 * 48, 5.0f);
    depth[7] = INFINITY; // the sky does not move under a translation
    const std::vector<float> step = motionBlurLengths(start, centre, end, depth);
    EXPECT_EQ(step[7], 0.0f);
    for (size_t i : {size_t(0), size_t(100), size_t(64 * 48 - 1)})
        EXPECT_NEAR(step[i], centre.fx * 0.1 / 5.0, 1e-5) << i; // planar depth is kept by a sideways step
    // A pan by +-a about the camera's vertical: the sky at the image centre moves 2 fx tan(a).
    const double a = 0.02;
    auto panned = [&](double angle) {
        Camera c = centre;
        c.worldFromCamera = centre.worldFromCamera * glm::dmat3(std::cos(angle), 0, -std::sin(angle), 0, 1, 0,
                                                                std::sin(angle), 0, std::cos(angle));
        return c;
    };
    std::fill(depth.begin(), depth.end(), INFINITY);
    const std::vector<float> pan = motionBlurLengths(panned(-a), centre, panned(a), depth);
    // Pixel (31, 23)'s centre is half a pixel off the optical axis in x and y: within 0.01 px of the axis's figure.
    EXPECT_NEAR(pan[23 * 64 + 31], 2.0 * centre.fx * std::tan(a), 0.01);
    EXPECT_GT(pan[0], pan[23 * 64 + 31]); // the corners move further
}

TEST(MotionBlur, MeanIsAFloatSumRoundedOnce) {
    ExposureMean mean;
    for (float v : {1.0f, 2.0f, 2.0f}) mean.add(std::vector<uint16_t>{floatToHalfBits(v), floatToHalfBits(-v)});
    const std::vector<uint16_t> out = mean.meanHalf();
    EXPECT_EQ(out[0], floatToHalfBits(5.0f / 3.0f));
    EXPECT_EQ(out[1], floatToHalfBits(-5.0f / 3.0f));
}

TEST_F(MotionBlurTest, ColourIsTheMeanOfInstantRendersAtTheSubFrameTimes) {
    SceneResources r =
        testScene({{"vehicles", nlohmann::json::array()},
                   {"camera.sensor", {{"shutter_s", 0.1}, {"motion_samples", 4}}}}); // static: no simulation
    RigCameras cameras;
    const std::optional<SensorModel> sensor = checkRigAndSensor(r, kWidth, kHeight, 0, cameras);
    ASSERT_TRUE(sensor);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    ASSERT_FALSE(gpu.simulation);
    OffscreenFrame target(*ctx, kWidth, kHeight, 1);
    const uint32_t frame = 3;
    const FrameImages blurred = renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, sensor, cameras);
    const FrameImages instant = renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, std::nullopt, cameras);

    const double t = frame * r.scene.sequence.timeStep, shutter = 0.1;
    auto times = [&](double stretch) {
        std::vector<double> out;
        for (double i : {0.5, 1.5, 2.5, 3.5}) out.push_back(t + stretch * shutter * (i / 4.0 - 0.5));
        return out;
    };
    const Mean mean = meanOfInstants(gpu, target, r, times(1.0), frame);
    EXPECT_LE(maxAbsDifference(blurred.rgbaHalf, mean.left), 1e-6);
    EXPECT_LE(maxAbsDifference(blurred.rightRgbaHalf, mean.right), 1e-6);
    // The test can fail: the instant, and the mean over an exposure twice as long, are other images.
    EXPECT_GT(maxAbsDifference(blurred.rgbaHalf, instant.rgbaHalf), 0.01);
    EXPECT_GT(maxAbsDifference(blurred.rgbaHalf, meanOfInstants(gpu, target, r, times(2.0), frame).left), 0.01);
    // The blur lengths: the left camera's motion between the exposure's ends at the truth depth; none without a shutter.
    EXPECT_EQ(blurred.motionBlur, motionBlurLengths(sequenceRigAt(r, kWidth, kHeight, t - 0.05).left, cameras.left,
                                                    sequenceRigAt(r, kWidth, kHeight, t + 0.05).left, blurred.depth));
    EXPECT_GT(*std::max_element(blurred.motionBlur.begin(), blurred.motionBlur.end()), 0.5f);
    EXPECT_TRUE(instant.motionBlur.empty());
    // The instant's colour comes out of the frame's own colour pass unchanged.
    EXPECT_EQ(instant.rgbaHalf, target.render(*gpu.renderer, cameras.left, t, frame, {}, &cameras.right).rgbaHalf);
}

// Ground truth (depth, labels, normals, flow of both views) of frames 0 and 1 with a shutter is that of the renders
// without one, bit for bit, with a rover pressing the plants (the interaction ticks once per frame, never per
// sub-frame) and render.flow (its next tick between the colour and the truth).
TEST_F(MotionBlurTest, TruthStaysTheInstantsBitwise) {
    struct Run {
        std::vector<FrameImages> frames;
        uint64_t nextTick = 0;
    };
    auto run = [&](bool shutter) {
        nlohmann::json overrides = {{"render.flow", true}};
        if (shutter) overrides["camera.sensor"] = {{"shutter_s", 0.1}, {"motion_samples", 3}};
        SceneResources r = testScene(overrides);
        RigCameras cameras;
        const std::optional<SensorModel> sensor = checkRigAndSensor(r, kWidth, kHeight, 0, cameras);
        EXPECT_EQ(bool(sensor), shutter);
        SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
        EXPECT_TRUE(gpu.simulation);
        OffscreenFrame target(*ctx, kWidth, kHeight, 1, true);
        Run out;
        for (uint32_t frame = 0; frame < 2; ++frame)
            out.frames.push_back(renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, sensor, cameras));
        out.nextTick = gpu.simulation ? gpu.simulation->nextTick() : 0;
        ctx->submitter.waitIdle();
        return out;
    };
    const Run sharp = run(false), blurred = run(true);
    EXPECT_EQ(sharp.nextTick, blurred.nextTick);
    for (size_t f = 0; f < 2; ++f) {
        const FrameImages &a = sharp.frames[f], &b = blurred.frames[f];
        EXPECT_TRUE(bitwiseEqual(a.depth, b.depth)) << "frame " << f;
        EXPECT_EQ(a.labels, b.labels) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.normals, b.normals)) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.rightDepth, b.rightDepth)) << "frame " << f;
        EXPECT_EQ(a.rightLabels, b.rightLabels) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.rightNormals, b.rightNormals)) << "frame " << f;
        EXPECT_FALSE(a.flowForward.empty());
        EXPECT_TRUE(bitwiseEqual(a.flowForward, b.flowForward)) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.flowBackward, b.flowBackward)) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.rightFlowForward, b.rightFlowForward)) << "frame " << f;
        EXPECT_TRUE(bitwiseEqual(a.rightFlowBackward, b.rightFlowBackward)) << "frame " << f;
        EXPECT_EQ(a.rgbaHalf.size(), b.rgbaHalf.size());
        EXPECT_GT(maxAbsDifference(a.rgbaHalf, b.rgbaHalf), 0.01) << "frame " << f; // the colour is blurred
        EXPECT_GT(maxAbsDifference(a.rightRgbaHalf, b.rightRgbaHalf), 0.01) << "frame " << f;
    }
}

// Noise, vignetting and distortion read out the exposure's mean (order: integrate the light, then the sensor).
TEST_F(MotionBlurTest, SensorReadsTheIntegratedLightOut) {
    const nlohmann::json shutter = {{"shutter_s", 0.1}, {"motion_samples", 4}};
    SceneResources r = testScene({{"vehicles", nlohmann::json::array()}, {"camera.sensor", shutter}});
    RigCameras cameras;
    const std::optional<SensorModel> plainSensor = checkRigAndSensor(r, kWidth, kHeight, 0, cameras);
    nlohmann::json noisy = shutter;
    noisy.update({{"electrons_per_unit", 400}, {"read_noise", 3}, {"vignetting", 0.4}, {"k1", -0.05}});
    const SensorParams noisyParams = parseSensor(noisy, "test", "camera.sensor");
    const std::optional<SensorModel> noisySensor(std::in_place, noisyParams, Intrinsics::of(cameras.left));
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    OffscreenFrame target(*ctx, kWidth, kHeight, 1);
    const uint32_t frame = 2;
    const FrameImages plain = renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, plainSensor, cameras);
    const FrameImages read = renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, noisySensor, cameras);
    std::vector<uint16_t> left = plain.rgbaHalf, right = plain.rightRgbaHalf;
    noisySensor->applyHalf(r.scene.seed, frame, 0, left);
    noisySensor->applyHalf(r.scene.seed, frame, 1, right);
    EXPECT_EQ(read.rgbaHalf, left);
    EXPECT_EQ(read.rightRgbaHalf, right);
    EXPECT_GT(maxAbsDifference(read.rgbaHalf, plain.rgbaHalf), 0.01); // the sensor did something
}

// The sun (a 0.5 degree HDR disc) seen by a camera panning at 2 rad/s about its own vertical axis over a 0.1 s
// exposure streaks along its row from u(-0.05 s) to u(0.05 s), u(t) = cx - fx tan(w t): 2 fx tan(0.1) pixels long.
// Measured between the two columns where the streak's energy crosses half its plateau.
TEST_F(MotionBlurTest, SunStreaksByThePannedAngle) {
    constexpr uint32_t kW = 160, kH = 120;
    SceneResources r = buildSceneResources(
        loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                        .overrides = R"({"render.resolution": [160, 120], "render.samples": 4, "vehicles": []})"}),
        false);
    SceneGpu gpu = createSceneGpu(*ctx, r, 4, SimulationMode::None);
    OffscreenFrame target(*ctx, kW, kH, 4);
    const glm::dvec3 position(50.0, 50.0, 30.0), sun = glm::dvec3(r.scene.sun.direction());
    const Camera start = Camera::lookAt(position, position + sun, {0, 0, 1}, 60.0, kW, kH);
    const double w = 2.0, shutter = 0.1;
    auto rigAt = [&](double t) {
        Camera c = start;
        const double a = w * t;
        c.worldFromCamera =
            start.worldFromCamera * glm::dmat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a));
        return RigCameras{c, c};
    };
    const ExposureColour streak =
        renderExposure(*gpu.renderer, target, rigAt, false, exposureTimes(0.0, shutter, 64), 0.0, 0, {});
    // Each column's energy over the sun's rows minus the sky's there (rows well above and below).
    std::vector<double> energy(kW, 0.0);
    auto luminance = [&](uint32_t x, uint32_t y) {
        const uint16_t* p = &streak.left[(size_t(y) * kW + x) * 4];
        return double(halfBitsToFloat(p[0])) + halfBitsToFloat(p[1]) + halfBitsToFloat(p[2]);
    };
    const uint32_t row = uint32_t(start.cy);
    for (uint32_t x = 0; x < kW; ++x) {
        const double sky = 0.5 * (luminance(x, row - 12) + luminance(x, row + 12));
        for (uint32_t y = row - 5; y <= row + 5; ++y) energy[x] += luminance(x, y) - sky;
    }
    const double predicted = 2.0 * start.fx * std::tan(w * shutter / 2.0);
    double plateau = 0.0;
    int plateauColumns = 0;
    for (uint32_t x = 0; x < kW; ++x)
        if (std::abs(x + 0.5 - start.cx) < predicted / 4.0) plateau += energy[x], ++plateauColumns;
    plateau /= plateauColumns;
    ASSERT_GT(plateau, 100.0);
    // Sub-pixel crossings of half the plateau, linear between column centres, outward from the middle.
    auto crossing = [&](int step) {
        int x = int(start.cx);
        while (x + step >= 0 && x + step < int(kW) && energy[x + step] > plateau / 2.0) x += step;
        const double inside = energy[x], outside = energy[x + step];
        return x + 0.5 + step * (inside - plateau / 2.0) / (inside - outside);
    };
    const double length = crossing(1) - crossing(-1);
    EXPECT_NEAR(length, predicted, 0.5) << "predicted " << predicted << " px";
    EXPECT_GT(predicted, 15.0); // a streak, not the 2-pixel disc
}

// sward-render with a shutter ("auto" sub-frames, noise, a rover pressing plants): a run in two shards, and a run
// resumed after a lost colour and blur file, write the very same files as one whole run.
TEST(MotionBlurDataset, ShardsAndResumedRunsWriteTheWholeRunsFiles) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 2.0}};
    scene["camera"]["sensor"] = {{"shutter_s", 0.05}, {"electrons_per_unit", 500}, {"read_noise", 2}};
    const std::string dir = sward::test::tempDir("motion-blur-shards"), path = dir + "/scene.json";
    std::ofstream(path) << scene.dump();
    std::string err;
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/whole --frames 0:3", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3 --shard " + shard, err), 0)
            << err;
    auto compare = [&] { return sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts"); };
    EXPECT_GT(compare(), 3u * 18); // every per-frame file of 3 stereo frames, motion_blur/ among them
    EXPECT_TRUE(std::filesystem::exists(dir + "/whole/motion_blur/000002.exr"));
    std::filesystem::remove(dir + "/parts/left/000001.exr");
    std::filesystem::remove(dir + "/parts/motion_blur/000002.exr");
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3", err), 0) << err;
    compare();
}
