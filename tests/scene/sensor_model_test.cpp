#include "scene/sensor_model.h"

#include "common/error.h"
#include "common/half_float.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

using namespace sward;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

Intrinsics testCamera() {
    return {100.0, 100.0, 80.0, 60.0, kWidth, kHeight};
}

std::vector<float> flatImage(float value, float alpha = 1.0f) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4, value);
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) rgba[p * 4 + 3] = alpha;
    return rgba;
}

// A deterministic, varied test image (including values a sensor could not produce).
std::vector<float> patternImage() {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float(i % 97) * 0.37f - 3.0f;
    rgba[5] = std::numeric_limits<float>::infinity();
    rgba[9] = std::bit_cast<float>(0x7fc01234u); // NaN with a payload
    return rgba;
}

bool bitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

SensorParams lens() {
    SensorParams p;
    p.enabled = true;
    p.k1 = -0.15; // barrel, monotonic well beyond the image corners of testCamera()
    p.k2 = 0.03;
    p.k3 = -0.002;
    p.p1 = 0.0015;
    p.p2 = -0.002;
    return p;
}

struct Moments {
    double mean = 0.0, variance = 0.0;
};

Moments moments(const std::vector<float>& rgba) {
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        sum += rgba[i];
        sum2 += double(rgba[i]) * rgba[i];
        ++n;
    }
    double mean = sum / double(n);
    return {mean, sum2 / double(n) - mean * mean};
}

} // namespace

TEST(SensorModel, DisabledIsBitwiseIdentity) {
    SensorParams off; // the default
    off.k1 = 0.3;     // parameters are ignored while disabled
    off.electronsPerUnit = 10.0;
    std::vector<float> image = patternImage(), original = image;
    applySensor(off, testCamera(), 1, 2, 3, image);
    EXPECT_TRUE(bitwiseEqual(image, original));

    std::vector<uint16_t> half(image.size());
    for (size_t i = 0; i < half.size(); ++i) half[i] = uint16_t(i * 7919u);
    std::vector<uint16_t> halfOriginal = half;
    applySensorHalf(off, testCamera(), 1, 2, 3, half);
    EXPECT_EQ(half, halfOriginal);
}

TEST(SensorModel, NeutralParametersAreBitwiseIdentity) {
    SensorParams neutral;
    neutral.enabled = true; // zero distortion, exposure 1, no vignetting, no noise
    std::vector<float> image = patternImage(), original = image;
    applySensor(neutral, testCamera(), 1, 2, 3, image);
    EXPECT_TRUE(bitwiseEqual(image, original));
}

// The forward model is OpenCV's: cv::projectPoints of a camera-space point lands where distortNormalized puts it.
TEST(SensorModel, DistortionMatchesOpenCvProjectPoints) {
    SensorParams p = lens();
    Intrinsics in = testCamera();
    cv::Matx33d k(in.fx, 0, in.cx, 0, in.fy, in.cy, 0, 0, 1);
    cv::Vec<double, 5> d(p.k1, p.k2, p.p1, p.p2, p.k3); // OpenCV's order
    std::vector<cv::Point3d> points = {{0.3, -0.2, 1.0}, {-0.7, 0.55, 1.0}, {0.05, 0.6, 2.0}, {-1.2, -0.9, 3.0}};
    std::vector<cv::Point2d> projected;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, d, projected);
    for (size_t i = 0; i < points.size(); ++i) {
        double xd, yd;
        distortNormalized(p, points[i].x / points[i].z, points[i].y / points[i].z, xd, yd);
        EXPECT_NEAR(in.fx * xd + in.cx, projected[i].x, 1e-9);
        EXPECT_NEAR(in.fy * yd + in.cy, projected[i].y, 1e-9);
        double x, y;
        undistortNormalized(p, xd, yd, x, y);
        EXPECT_NEAR(x, points[i].x / points[i].z, 1e-12);
        EXPECT_NEAR(y, points[i].y / points[i].z, 1e-12);
    }
}

// The distorted image shows at pixel (u, v) the ideal point that OpenCV's model maps to (u, v). The ideal image
// stores its own pixel-centre coordinates in R and G, which bilinear sampling reproduces exactly, so every
// output pixel tells where it sampled; projecting that ideal point with cv::projectPoints must give back the
// output pixel's centre.
TEST(SensorModel, DistortedPixelShowsTheIdealPointOpenCvProjectsThere) {
    SensorParams p = lens();
    Intrinsics in = testCamera();
    std::vector<float> image(size_t(kWidth) * kHeight * 4);
    for (uint32_t j = 0; j < kHeight; ++j)
        for (uint32_t i = 0; i < kWidth; ++i) {
            float* px = &image[(size_t(j) * kWidth + i) * 4];
            px[0] = float(i) + 0.5f, px[1] = float(j) + 0.5f, px[2] = 1.0f, px[3] = 1.0f;
        }
    applySensor(p, in, 0, 0, 0, image);

    cv::Matx33d k(in.fx, 0, in.cx, 0, in.fy, in.cy, 0, 0, 1);
    cv::Vec<double, 5> d(p.k1, p.k2, p.p1, p.p2, p.k3);
    std::vector<cv::Point3d> ideal;
    std::vector<cv::Point2d> expected;
    for (uint32_t j = 0; j < kHeight; ++j)
        for (uint32_t i = 0; i < kWidth; ++i) {
            const float* px = &image[(size_t(j) * kWidth + i) * 4];
            // Only pixels whose ideal point lies inside the rendered image (elsewhere the sample is clamped).
            if (!(px[0] > 0.5f && px[0] < kWidth - 0.5f && px[1] > 0.5f && px[1] < kHeight - 0.5f)) continue;
            ideal.emplace_back((px[0] - in.cx) / in.fx, (px[1] - in.cy) / in.fy, 1.0);
            expected.emplace_back(i + 0.5, j + 0.5);
        }
    ASSERT_GT(ideal.size(), size_t(kWidth) * kHeight / 2);
    std::vector<cv::Point2d> projected;
    cv::projectPoints(ideal, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, d, projected);
    double worst = 0.0;
    for (size_t n = 0; n < ideal.size(); ++n) worst = std::max(worst, cv::norm(projected[n] - expected[n]));
    EXPECT_LT(worst, 1e-3) << "pixels";

    // Barrel distortion (k1 < 0) pulls the ideal image's edge inwards: the output corner shows a point
    // outside the render, the centre pixel is nearly unmoved.
    const float* centre = &image[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4];
    EXPECT_NEAR(centre[0], kWidth / 2 + 0.5f, 0.05f);
    EXPECT_NEAR(centre[1], kHeight / 2 + 0.5f, 0.05f);
}

TEST(SensorModel, NonInvertibleDistortionIsRefused) {
    SensorParams p;
    p.enabled = true;
    p.k1 = -1.5; // folds over at r^2 = 1/(3*1.5): inside a 160 px wide image at f = 100
    EXPECT_THROW(SensorModel(p, testCamera()), Error);
}

TEST(SensorModel, VignettingDarkensCornersByCos4) {
    SensorParams p;
    p.enabled = true;
    p.vignetting = 1.0;
    Intrinsics in = testCamera();
    std::vector<float> image = flatImage(2.0f);
    applySensor(p, in, 0, 0, 0, image);
    auto expectedGain = [&](uint32_t i, uint32_t j, double strength) {
        double x = (i + 0.5 - in.cx) / in.fx, y = (j + 0.5 - in.cy) / in.fy;
        double cos2 = 1.0 / (1.0 + x * x + y * y);
        return 1.0 - strength + strength * cos2 * cos2;
    };
    const float* corner = &image[0];
    EXPECT_NEAR(corner[0], 2.0 * expectedGain(0, 0, 1.0), 1e-6);
    EXPECT_NEAR(corner[0], 2.0 * std::pow(1.0 + (79.5 * 79.5 + 59.5 * 59.5) / 1e4, -2.0), 1e-6); // ~0.41 of centre
    EXPECT_EQ(corner[3], 1.0f);                                                                  // alpha untouched
    const float* centre = &image[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4];
    EXPECT_NEAR(centre[1], 2.0, 1e-3);

    p.vignetting = 0.5;
    image = flatImage(2.0f);
    applySensor(p, in, 0, 0, 0, image);
    size_t last = (size_t(kHeight - 1) * kWidth + kWidth - 1) * 4;
    EXPECT_NEAR(image[last + 2], 2.0 * expectedGain(kWidth - 1, kHeight - 1, 0.5), 1e-6);
}

TEST(SensorModel, ExposureScalesLinearly) {
    SensorParams p = parseSensor({{"exposure_ev", 1.5}}, "s.json", "camera.sensor");
    std::vector<float> image = flatImage(0.25f);
    applySensor(p, testCamera(), 0, 0, 0, image);
    EXPECT_FLOAT_EQ(image[0], 0.25f * float(std::exp2(1.5)));
    EXPECT_EQ(image[3], 1.0f);
}

// Flat image of radiance L: output mean L, variance (L*g + read^2) / g^2 with g electrons per unit.
TEST(SensorModel, ShotAndReadNoiseHaveTheModelledMoments) {
    SensorParams p;
    p.enabled = true;
    p.electronsPerUnit = 1000.0;
    p.readNoise = 5.0;
    const double n = double(kWidth) * kHeight * 3;
    for (double radiance : {0.5, 0.02, 0.0}) {
        std::vector<float> image = flatImage(float(radiance));
        applySensor(p, testCamera(), 7, 3, 0, image);
        double variance = (radiance * 1000.0 + 25.0) / 1e6;
        Moments m = moments(image);
        EXPECT_NEAR(m.mean, radiance, 5.0 * std::sqrt(variance / n)) << radiance;      // 5 sigma
        EXPECT_NEAR(m.variance / variance, 1.0, 5.0 * std::sqrt(2.0 / n)) << radiance; // 5 sigma
        // Gaussian shape: about 68.27 % within one standard deviation.
        size_t inside = 0;
        for (size_t i = 0; i < image.size(); ++i)
            if (i % 4 != 3 && std::abs(image[i] - radiance) < std::sqrt(variance)) ++inside;
        EXPECT_NEAR(double(inside) / n, 0.6827, 0.01) << radiance;
        EXPECT_EQ(image[3], 1.0f);
    }
}

TEST(SensorModel, NoiseIsUncorrelatedBetweenNeighboursAndChannels) {
    SensorParams p;
    p.enabled = true;
    p.electronsPerUnit = 100.0;
    std::vector<float> image = flatImage(1.0f);
    applySensor(p, testCamera(), 11, 0, 1, image);
    double horizontal = 0.0, channels = 0.0;
    size_t count = 0;
    for (size_t px = 0; px + 1 < size_t(kWidth) * kHeight; ++px, ++count) {
        horizontal += (image[px * 4] - 1.0) * (image[(px + 1) * 4] - 1.0);
        channels += (image[px * 4] - 1.0) * (image[px * 4 + 1] - 1.0);
    }
    double variance = 1.0 / 100.0;
    EXPECT_NEAR(horizontal / double(count) / variance, 0.0, 5.0 / std::sqrt(double(count)));
    EXPECT_NEAR(channels / double(count) / variance, 0.0, 5.0 / std::sqrt(double(count)));
}

TEST(SensorModel, FullWellClipsElectrons) {
    SensorParams p;
    p.enabled = true;
    p.electronsPerUnit = 1000.0;
    p.fullWell = 800.0;
    std::vector<float> image = flatImage(5.0f);
    applySensor(p, testCamera(), 0, 0, 0, image);
    for (size_t i = 0; i < image.size(); ++i)
        if (i % 4 != 3) {
            ASSERT_LE(image[i], 0.8f);
        }
}

// Same inputs, same bits; any change of seed, frame or camera gives different noise.
TEST(SensorModel, NoiseIsDeterministicAndKeyed) {
    SensorParams p = lens();
    p.vignetting = 0.3;
    p.electronsPerUnit = 200.0;
    p.readNoise = 2.0;
    SensorModel model(p, testCamera());
    auto run = [&](uint64_t seed, uint32_t frame, uint32_t camera) {
        std::vector<float> image = flatImage(0.4f);
        model.apply(seed, frame, camera, image);
        return image;
    };
    std::vector<float> reference = run(5, 10, 0);
    EXPECT_TRUE(bitwiseEqual(reference, run(5, 10, 0)));
    std::vector<float> oneShot = flatImage(0.4f);
    applySensor(p, testCamera(), 5, 10, 0, oneShot);
    EXPECT_TRUE(bitwiseEqual(reference, oneShot));
    EXPECT_FALSE(bitwiseEqual(reference, run(6, 10, 0)));
    EXPECT_FALSE(bitwiseEqual(reference, run(5, 11, 0)));
    EXPECT_FALSE(bitwiseEqual(reference, run(5, 10, 1)));
}

TEST(SensorModel, HalfVariantRoundsTheFloatResult) {
    SensorParams p = lens();
    p.electronsPerUnit = 500.0;
    std::vector<uint16_t> half(size_t(kWidth) * kHeight * 4);
    std::vector<float> image(half.size());
    for (size_t i = 0; i < half.size(); ++i) {
        half[i] = floatToHalfBits(float(i % 251) / 50.0f);
        image[i] = halfBitsToFloat(half[i]);
    }
    applySensorHalf(p, testCamera(), 9, 4, 1, half);
    applySensor(p, testCamera(), 9, 4, 1, image);
    for (size_t i = 0; i < half.size(); ++i) ASSERT_EQ(half[i], floatToHalfBits(image[i])) << i;
}

TEST(SensorModel, ParsesEveryKeyAndRoundTripsThroughJson) {
    nlohmann::json j = {{"exposure", 0.8},   {"vignetting", 0.4}, {"k1", -0.1},  {"k2", 0.01},
                        {"k3", 0.001},       {"p1", 1e-4},        {"p2", -2e-4}, {"electrons_per_unit", 3000},
                        {"read_noise", 3.5}, {"full_well", 20000}};
    SensorParams p = parseSensor(j, "s.json", "camera.sensor");
    EXPECT_TRUE(p.enabled); // a sensor object is on unless it says "enabled": false
    EXPECT_EQ(p.exposure, 0.8);
    EXPECT_EQ(p.vignetting, 0.4);
    EXPECT_EQ(p.k1, -0.1);
    EXPECT_EQ(p.p2, -2e-4);
    EXPECT_EQ(p.electronsPerUnit, 3000.0);
    EXPECT_EQ(p.readNoise, 3.5);
    EXPECT_EQ(p.fullWell, 20000.0);
    EXPECT_EQ(sensorToJson(parseSensor(sensorToJson(p), "s.json", "x")), sensorToJson(p));
    EXPECT_FALSE(parseSensor(nlohmann::json(), "s.json", "camera.sensor").enabled);
    EXPECT_FALSE(parseSensor({{"enabled", false}, {"k1", 0.2}}, "s.json", "camera.sensor").enabled);
}

TEST(SensorModel, ParseErrorsNameTheJsonPath) {
    auto message = [&](const nlohmann::json& j) {
        return test::errorOf([&] { parseSensor(j, "scene.json", "rigs[0].sensor"); });
    };
    EXPECT_EQ(message({{"k1", "strong"}}), "scene.json: 'rigs[0].sensor.k1' must be a number");
    EXPECT_EQ(message({{"vignetting", 1.5}}),
              "scene.json: 'rigs[0].sensor.vignetting' must be between 0 and 1 (got 1.5)");
    EXPECT_EQ(message({{"exposure", 0}}),
              "scene.json: 'rigs[0].sensor.exposure' must be between 1e-09 and 1e+09 (got 0)");
    EXPECT_EQ(message({{"k4", 0.1}}), "scene.json: unknown key 'rigs[0].sensor.k4'");
    EXPECT_EQ(message({{"enabled", 1}}), "scene.json: 'rigs[0].sensor.enabled' must be true or false");
    EXPECT_EQ(message({{"exposure", 2}, {"exposure_ev", 1}}),
              "scene.json: 'rigs[0].sensor' must give either 'exposure' or 'exposure_ev', not both");
    EXPECT_EQ(
        message({{"read_noise", 2}}),
        "scene.json: 'rigs[0].sensor.electrons_per_unit' must be positive when 'read_noise' or 'full_well' is set");
    EXPECT_EQ(message(nlohmann::json::array()), "scene.json: 'rigs[0].sensor' must be an object");
}

TEST(SensorModel, ShutterKeysParseAndRoundTrip) {
    SensorParams p = parseSensor({{"shutter_s", 0.004}, {"motion_samples", 8}}, "s.json", "camera.sensor");
    EXPECT_EQ(p.shutterSeconds, 0.004);
    EXPECT_EQ(p.motionSamples, 8u);
    EXPECT_EQ(sensorToJson(parseSensor(sensorToJson(p), "s.json", "x")), sensorToJson(p));
    EXPECT_EQ(parseSensor({{"shutter_s", 0.01}, {"motion_samples", "auto"}}, "s", "c").motionSamples, 0u);
    EXPECT_EQ(parseSensor({{"shutter_s", 0.01}, {"motion_samples", 0}}, "s", "c").motionSamples, 0u);
    EXPECT_EQ(sensorToJson(parseSensor({{"shutter_s", 0.01}}, "s", "c")).at("motion_samples"), "auto");
    EXPECT_EQ(parseSensor({{"motion_samples", 64}}, "s", "c").motionSamples, 64u);
    // Without a shutter the records stay as they were before the keys existed.
    const nlohmann::json noShutter = sensorToJson(parseSensor({{"k1", 0.1}}, "s", "c"));
    EXPECT_FALSE(noShutter.contains("shutter_s"));
    EXPECT_FALSE(noShutter.contains("motion_samples"));
}

TEST(SensorModel, ShutterKeyErrorsNameTheKey) {
    auto message = [&](const nlohmann::json& j) {
        return test::errorOf([&] { parseSensor(j, "scene.json", "camera.sensor"); });
    };
    EXPECT_EQ(message({{"shutter_s", -0.01}}),
              "scene.json: 'camera.sensor.shutter_s' must be between 0 and 1 (got -0.01)");
    EXPECT_EQ(message({{"shutter_s", 2}}), "scene.json: 'camera.sensor.shutter_s' must be between 0 and 1 (got 2)");
    EXPECT_EQ(message({{"shutter_s", "fast"}}), "scene.json: 'camera.sensor.shutter_s' must be a number");
    const std::string samples = "scene.json: 'camera.sensor.motion_samples' must be \"auto\", 0 (auto) or an integer "
                                "in [2, 64] (got ";
    EXPECT_EQ(message({{"motion_samples", 1}}), samples + "1)");
    EXPECT_EQ(message({{"motion_samples", 65}}), samples + "65)");
    EXPECT_EQ(message({{"motion_samples", -4}}), samples + "-4)");
    EXPECT_EQ(message({{"motion_samples", 4.5}}), samples + "4.5)");
    EXPECT_EQ(message({{"motion_samples", "many"}}), samples + "\"many\")");
    EXPECT_EQ(message({{"motion_samples", nullptr}}), samples + "null)");
}
