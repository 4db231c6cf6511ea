// The sensor's electronics (scene/sensor_exposure.h): gain / ISO, read noise before and after the gain, the ADC's
// clipping, black level and white balance, each by its exact effect on applySensor's output.
#include "scene/sensor_exposure.h"
#include "scene/sensor_model.h"

#include "common/error.h"
#include "common/half_float.h"
#include "common/json_reader.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace sward;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

Intrinsics testCamera() {
    return {100.0, 100.0, 80.0, 60.0, kWidth, kHeight};
}

std::vector<float> flatImage(float value) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4, value);
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) rgba[p * 4 + 3] = 1.0f;
    return rgba;
}

// Colour values 0.05 .. 2.0, all exact binary fractions (k / 64).
std::vector<float> rampImage() {
    std::vector<float> rgba = flatImage(0.0f);
    for (size_t i = 0; i < rgba.size(); ++i)
        if (i % 4 != 3) rgba[i] = float(3 + i % 126) / 64.0f;
    return rgba;
}

SensorParams parse(const nlohmann::json& j) {
    return parseSensor(j, "scene.json", "camera.sensor");
}

std::vector<float> sensed(const nlohmann::json& j, std::vector<float> rgba) {
    applySensor(parse(j), testCamera(), 7, 3, 0, rgba);
    return rgba;
}

bool bitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

struct Moments {
    double mean = 0.0, std = 0.0;
};

// Over the colour channels `first`..`last` of every pixel.
Moments moments(const std::vector<float>& rgba, int first = 0, int last = 2) {
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < rgba.size(); ++i) {
        const int c = int(i % 4);
        if (c < first || c > last) continue;
        sum += rgba[i];
        sum2 += double(rgba[i]) * rgba[i];
        ++n;
    }
    const double mean = sum / double(n);
    return {mean, std::sqrt(sum2 / double(n) - mean * mean)};
}

const nlohmann::json kNoisy = {{"electrons_per_unit", 2000}, {"read_noise", 3}};

} // namespace

TEST(SensorExposure, NeutralValuesOfTheNewKeysLeaveTheImageBitwise) {
    nlohmann::json neutral = kNoisy;
    neutral["iso"] = 250;
    neutral["base_iso"] = 250;
    neutral["white_balance"] = {1, 1, 1};
    nlohmann::json unity = kNoisy;
    unity["gain"] = 1;
    const std::vector<float> plain = sensed(kNoisy, rampImage());
    EXPECT_FALSE(bitwiseEqual(plain, rampImage())); // the noise is there
    EXPECT_TRUE(bitwiseEqual(sensed(neutral, rampImage()), plain));
    EXPECT_TRUE(bitwiseEqual(sensed(unity, rampImage()), plain));
}

TEST(SensorExposure, GainScalesSignalAndNoiseExactly) {
    nlohmann::json iso400 = kNoisy;
    iso400["iso"] = 400; // base ISO 100: G = 4
    const std::vector<float> base = sensed(kNoisy, rampImage()), gained = sensed(iso400, rampImage());
    for (size_t i = 0; i < base.size(); ++i)
        ASSERT_EQ(gained[i], i % 4 == 3 ? base[i] : 4.0f * base[i]) << i; // the same electrons, amplified
    // Without electrons (no noise) the gain is a plain factor on the light.
    const std::vector<float> clean = sensed({{"gain", 2.5}}, rampImage()), ramp = rampImage();
    for (size_t i = 0; i < clean.size(); ++i) ASSERT_EQ(clean[i], i % 4 == 3 ? ramp[i] : float(2.5 * ramp[i])) << i;
}

TEST(SensorExposure, HigherGainAtShorterExposureKeepsTheMeanAndRaisesTheNoise) {
    // Shot-noise limited: at the same mean, a quarter of the electrons have twice the relative noise.
    const nlohmann::json bright = {{"electrons_per_unit", 400}};
    const nlohmann::json dim = {{"electrons_per_unit", 400}, {"exposure", 0.25}, {"iso", 400}};
    const Moments a = moments(sensed(bright, flatImage(0.5f))), b = moments(sensed(dim, flatImage(0.5f)));
    EXPECT_NEAR(a.mean, 0.5, 0.002);
    EXPECT_NEAR(b.mean, 0.5, 0.004);
    EXPECT_NEAR(a.std, std::sqrt(0.5 * 400) / 400, 0.002); // 0.0354
    EXPECT_NEAR(b.std / a.std, 2.0, 0.05);
}

TEST(SensorExposure, ReadNoiseAfterTheGainIsNotAmplified) {
    // No light: only read noise. 5 e- before a gain of 8 is 0.4 in the output at 100 e- per unit; 5 e- after it 0.05.
    const nlohmann::json before = {{"electrons_per_unit", 100}, {"read_noise", 5}, {"gain", 8}};
    const nlohmann::json after = {{"electrons_per_unit", 100}, {"read_noise_after_gain", 5}, {"gain", 8}};
    const Moments b = moments(sensed(before, flatImage(0.0f))), a = moments(sensed(after, flatImage(0.0f)));
    EXPECT_NEAR(b.std, 0.4, 0.4 * 0.02);
    EXPECT_NEAR(a.std, 0.05, 0.05 * 0.02);
    EXPECT_NEAR(a.mean, 0.0, 0.002);
}

TEST(SensorExposure, AdcClipsAtTheFullWellAtUnityGain) {
    // 100 units of light fill any well: at G = 2 the ADC clips at full_well / epu in the output, at G = 0.5 the well
    // clips first and the output tops out at half of that.
    const nlohmann::json high = {{"electrons_per_unit", 100}, {"full_well", 1000}, {"gain", 2}};
    const nlohmann::json low = {{"electrons_per_unit", 100}, {"full_well", 1000}, {"gain", 0.5}};
    for (float v : sensed(high, flatImage(100.0f))) ASSERT_TRUE(v == 10.0f || v == 1.0f) << v;
    for (float v : sensed(low, flatImage(100.0f))) ASSERT_TRUE(v == 5.0f || v == 1.0f) << v;
    // At G = 2, 7 units of light (700 e-, 1400 after the gain: 7.5 sigma above the clip) clip too; 4 units do not.
    EXPECT_EQ(moments(sensed(high, flatImage(7.0f))).std, 0.0);
    EXPECT_GT(moments(sensed(high, flatImage(4.0f))).std, 0.1);
}

TEST(SensorExposure, BlackLevelIsKeptAndTheOutputFlooredAtZero) {
    const std::vector<float> ramp = rampImage();
    const std::vector<float> clean = sensed({{"black_level", 0.125}}, ramp);
    for (size_t i = 0; i < clean.size(); ++i) ASSERT_EQ(clean[i], i % 4 == 3 ? ramp[i] : ramp[i] + 0.125f) << i;
    // Read noise on no light: without a black level the output is zero-mean, with black level 0 half of it floors
    // at 0, with a pedestal of 10 sigma none does and the mean is the pedestal.
    const nlohmann::json dark = {{"electrons_per_unit", 100}, {"read_noise", 2}}; // sigma 0.02
    nlohmann::json floored = dark, pedestal = dark;
    floored["black_level"] = 0;
    pedestal["black_level"] = 0.2;
    const std::vector<float> zeroMean = sensed(dark, flatImage(0.0f)), clipped = sensed(floored, flatImage(0.0f));
    const std::vector<float> lifted = sensed(pedestal, flatImage(0.0f));
    EXPECT_LT(*std::min_element(zeroMean.begin(), zeroMean.end()), -0.05f);
    EXPECT_EQ(*std::min_element(clipped.begin(), clipped.end()), 0.0f);
    const size_t zeros = size_t(std::count(clipped.begin(), clipped.end(), 0.0f));
    EXPECT_NEAR(double(zeros) / (kWidth * kHeight * 3), 0.5, 0.02);
    for (size_t i = 0; i < zeroMean.size(); ++i)
        if (i % 4 != 3) {
            ASSERT_EQ(clipped[i], std::max(zeroMean[i], 0.0f)) << i;
        }
    EXPECT_NEAR(moments(lifted).mean, 0.2, 0.001);
    // The white level is the pedestal plus the well.
    nlohmann::json full = pedestal;
    full["full_well"] = 1000;
    for (float v : sensed(full, flatImage(50.0f))) ASSERT_TRUE(v == 10.2f || v == 1.0f) << v;
}

TEST(SensorExposure, WhiteBalanceMultipliesEachChannelAfterTheNoise) {
    const std::vector<float> ramp = rampImage();
    const std::vector<float> clean = sensed({{"white_balance", {2.0, 1.0, 0.75}}}, ramp);
    const double wb[3] = {2.0, 1.0, 0.75};
    for (size_t i = 0; i < clean.size(); ++i)
        ASSERT_EQ(clean[i], i % 4 == 3 ? ramp[i] : float(wb[i % 4] * ramp[i])) << i;
    // With noise: the red channel is twice the unbalanced one, its noise included (a digital gain on the raw).
    nlohmann::json balanced = kNoisy;
    balanced["white_balance"] = {2.0, 1.0, 1.0};
    const std::vector<float> plain = sensed(kNoisy, ramp), red = sensed(balanced, ramp);
    for (size_t i = 0; i < plain.size(); ++i) ASSERT_EQ(red[i], i % 4 == 0 ? 2.0f * plain[i] : plain[i]) << i;
}

TEST(SensorExposure, ParsesEveryKeyAndWritesBackOnlyThoseSet) {
    const SensorParams p = parse({{"electrons_per_unit", 1000},
                                  {"iso", 800},
                                  {"base_iso", 200},
                                  {"read_noise_after_gain", 1.5},
                                  {"black_level", 0.01},
                                  {"white_balance", {1.8, 1.0, 1.4}}});
    EXPECT_EQ(p.electronics.gain, 4.0);
    EXPECT_EQ(p.electronics.readNoiseAfterGain, 1.5);
    EXPECT_EQ(p.electronics.blackLevel, 0.01);
    EXPECT_EQ(p.electronics.whiteBalance, (std::array<double, 3>{1.8, 1.0, 1.4}));
    const nlohmann::json written = sensorToJson(p);
    EXPECT_EQ(written.at("iso"), 800.0);
    EXPECT_EQ(written.at("base_iso"), 200.0);
    EXPECT_EQ(sensorToJson(parse(written)), written);
    EXPECT_EQ(sensorToJson(parse({{"gain", 3}})).at("gain"), 3.0);
    // Decibels of amplitude: 20 dB is 10 x, 6.0206 dB about 2 x; written back as given.
    EXPECT_NEAR(parse({{"gain_db", 20}}).electronics.gain, 10.0, 1e-14);
    EXPECT_NEAR(parse({{"gain_db", -40}}).electronics.gain, 0.01, 1e-17);
    EXPECT_NEAR(parse({{"gain_db", 6.0206}}).electronics.gain, 2.0, 1e-5);
    EXPECT_EQ(sensorToJson(parse({{"gain_db", 12}})).at("gain_db"), 12.0);
    EXPECT_FALSE(sensorToJson(parse({{"gain_db", 12}})).contains("gain"));
    // A sensor without them is written with the keys it always had: frames.jsonl of older scenes is unchanged.
    EXPECT_EQ(sensorToJson(parse(kNoisy)).size(), 11u);
    EXPECT_TRUE(parse(kNoisy).electronics.isDefault());
}

TEST(SensorExposure, BadValuesAreRefusedNamingTheKey) {
    auto message = [&](const nlohmann::json& j) {
        return test::errorOf([&] { parseSensor(j, "scene.json", "camera.sensor"); });
    };
    EXPECT_EQ(message({{"gain", 0}}), "scene.json: 'camera.sensor.gain' must be between 0.001 and 10000 (got 0)");
    EXPECT_EQ(message({{"gain", 2}, {"iso", 200}}),
              "scene.json: 'camera.sensor' must give one of 'gain', 'gain_db' or 'iso' (with 'base_iso')");
    EXPECT_EQ(message({{"gain_db", 6}, {"base_iso", 200}}),
              "scene.json: 'camera.sensor' must give one of 'gain', 'gain_db' or 'iso' (with 'base_iso')");
    EXPECT_EQ(message({{"gain_db", 81}}), "scene.json: 'camera.sensor.gain_db' must be between -60 and 80 (got 81)");
    EXPECT_EQ(message({{"iso", 0.5}}), "scene.json: 'camera.sensor.iso' must be between 1 and 1e+07 (got 0.5)");
    EXPECT_EQ(message({{"base_iso", 100}}), "scene.json: 'camera.sensor.base_iso' needs 'iso'");
    EXPECT_EQ(message({{"iso", 1e7}, {"base_iso", 1}}),
              "scene.json: 'camera.sensor.iso' / 'base_iso' must give a gain between 0.001 and 10000 (got 1e+07)");
    EXPECT_EQ(message({{"read_noise_after_gain", 2}}),
              "scene.json: 'camera.sensor.electrons_per_unit' must be positive when 'read_noise_after_gain' is set");
    EXPECT_EQ(message({{"electrons_per_unit", 10}, {"read_noise_after_gain", -1}}),
              "scene.json: 'camera.sensor.read_noise_after_gain' must be between 0 and 1e+09 (got -1)");
    EXPECT_EQ(message({{"black_level", -0.1}}),
              "scene.json: 'camera.sensor.black_level' must be between 0 and 10000 (got -0.1)");
    EXPECT_EQ(message({{"black_level", "low"}}), "scene.json: 'camera.sensor.black_level' must be a number");
    EXPECT_EQ(message({{"white_balance", {1, 1}}}),
              "scene.json: 'camera.sensor.white_balance' must be an array of 3 numbers");
    EXPECT_EQ(message({{"white_balance", {1, 0, 1}}}),
              "scene.json: 'camera.sensor.white_balance' must hold numbers between 0.001 and 1000");
}

namespace {

// The exposure of every frame of `meters`, each from the meters of the frames up to it.
std::vector<double> exposures(const AutoExposureParams& p, double timeStep, const std::vector<double>& meters) {
    std::vector<double> out;
    for (size_t k = 0; k < meters.size(); ++k)
        out.push_back(autoExposureFactor(p, timeStep, std::span(meters).first(k + 1)));
    return out;
}

} // namespace

TEST(AutoExposure, FollowsAStepInTheSceneWithinItsTimeConstant) {
    // 30 fps, tau 0.5 s (15 frames): a bright view (mean luminance 1.0) for 40 frames, then a dark one (1/32).
    const AutoExposureParams p{.enabled = true, .targetGrey = 0.18, .timeConstantSeconds = 0.5};
    const double dt = 1.0 / 30.0;
    std::vector<double> meters(40, 1.0);
    meters.resize(200, 1.0 / 32.0);
    const std::vector<double> e = exposures(p, dt, meters);
    EXPECT_EQ(autoExposureWindow(p, dt), 75u);
    EXPECT_NEAR(e[39], 0.18, 1e-15);
    const double before = std::log2(0.18), after = std::log2(0.18 * 32.0); // 5 stops to go
    const auto followed = [&](size_t k) { return (std::log2(e[k]) - before) / (after - before); };
    EXPECT_LT(followed(40), 0.1);   // the step's own frame moves the exposure by one weight's share
    EXPECT_GE(followed(55), 0.632); // one time constant later: 1 - 1/e of the way (the window's start helps a little)
    EXPECT_LT(followed(55), 0.7);
    for (size_t k = 41; k <= 40 + 75; ++k) ASSERT_GT(e[k], e[k - 1]) << k; // monotonic, no overshoot
    for (size_t k = 40 + 75; k < e.size(); ++k) ASSERT_EQ(e[k], e[40 + 75]) << k;
    EXPECT_NEAR(e[40 + 75], 0.18 * 32.0, 1e-12); // the window holds only the dark view: exactly there
    // And back up into the light at the same pace, in stops.
    std::vector<double> up(40, 1.0 / 32.0);
    up.resize(120, 1.0);
    const std::vector<double> u = exposures(p, dt, up);
    EXPECT_NEAR((std::log2(u[55]) - after) / (before - after), followed(55), 1e-9);
}

TEST(AutoExposure, AShardOrResumedRunRecomputesEveryExposureBitwise) {
    // A shard starting at frame f re-meters frames f - W .. f - 1 only: the exposure is the one of the whole run.
    const AutoExposureParams p{.enabled = true, .targetGrey = 0.2, .timeConstantSeconds = 0.25};
    const double dt = 0.05;
    const uint32_t w = autoExposureWindow(p, dt);
    ASSERT_EQ(w, 25u);
    std::vector<double> meters;
    for (int k = 0; k < 300; ++k) meters.push_back(0.05 + 0.9 * double((k * 7919) % 101) / 100.0);
    const std::vector<double> whole = exposures(p, dt, meters);
    for (size_t k = 0; k < meters.size(); ++k) {
        const size_t first = k >= w ? k - w : 0;
        const std::vector<double> window(meters.begin() + long(first), meters.begin() + long(k) + 1);
        ASSERT_EQ(autoExposureFactor(p, dt, window), whole[k]) << k;
    }
    // A meter outside the window changes nothing; one inside changes the exposure.
    std::vector<double> changed = meters;
    changed[100 - w - 1] = 50.0;
    EXPECT_EQ(autoExposureFactor(p, dt, std::span(changed).first(101)), whole[100]);
    changed[100 - w] = 50.0;
    EXPECT_NE(autoExposureFactor(p, dt, std::span(changed).first(101)), whole[100]);
}

TEST(AutoExposure, LimitsClampTheExposureInStops) {
    const AutoExposureParams p{
        .enabled = true, .targetGrey = 0.18, .timeConstantSeconds = 0.0, .minEv = -1.5, .maxEv = 2.0};
    EXPECT_EQ(autoExposureFactor(p, 0.1, std::vector<double>{100.0}), exactExp2(-1.5));
    EXPECT_EQ(autoExposureFactor(p, 0.1, std::vector<double>{1e-3}), 4.0);
    EXPECT_EQ(autoExposureFactor(p, 0.1, std::vector<double>{0.0}), 4.0); // a black view opens up to the limit
    EXPECT_NEAR(autoExposureFactor(p, 0.1, std::vector<double>{0.09}), 2.0, 1e-15);
    EXPECT_EQ(autoExposureWindow(p, 0.1), 0u); // tau 0: each frame metered alone
}

TEST(AutoExposure, ExactLog2AndExp2AgreeWithLibmAndAreExactOnPowersOfTwo) {
    for (int n = -30; n <= 30; ++n) {
        EXPECT_EQ(exactExp2(double(n)), std::ldexp(1.0, n));
        EXPECT_EQ(exactLog2(std::ldexp(1.0, n)), double(n));
    }
    for (double x = -20.0; x <= 20.0; x += 0.0137)
        EXPECT_NEAR(exactExp2(x) / std::exp2(x), 1.0, 1e-15) << x; // a few ulp
    for (double x = 1e-6; x < 1e6; x *= 1.37) EXPECT_NEAR(exactLog2(x), std::log2(x), 4e-15) << x;
}

TEST(AutoExposure, MeterIsTheMeanLuminanceOfTheFinitePixels) {
    // Two pixels (1, 0, 0) and (0, 1, 0.5) and one with an infinite channel, which the meter leaves out.
    const std::vector<uint16_t> image = {floatToHalfBits(1.0f),
                                         0,
                                         0,
                                         floatToHalfBits(1.0f),
                                         0,
                                         floatToHalfBits(1.0f),
                                         floatToHalfBits(0.5f),
                                         floatToHalfBits(1.0f),
                                         floatToHalfBits(INFINITY),
                                         0,
                                         0,
                                         floatToHalfBits(1.0f)};
    EXPECT_NEAR(meterLuminance(image), (0.2126 + 0.7152 + 0.0722 * 0.5) / 2.0, 1e-15);
    EXPECT_EQ(meterLuminance({}), 0.0);
}

TEST(AutoExposure, ParsesItsObjectAndNamesBadKeys) {
    auto parseAe = [](const nlohmann::json& ae) {
        const nlohmann::json sensor = {{"auto_exposure", ae}};
        JsonReader r(sensor, "scene.json", "camera.sensor");
        return parseAutoExposure(r);
    };
    const AutoExposureParams p =
        parseAe({{"target_grey", 0.25}, {"time_constant_s", 0.8}, {"min_ev", -4}, {"max_ev", 3.5}});
    EXPECT_TRUE(p.enabled);
    EXPECT_EQ(p.targetGrey, 0.25);
    EXPECT_EQ(p.timeConstantSeconds, 0.8);
    EXPECT_EQ(p.minEv, -4.0);
    EXPECT_EQ(p.maxEv, 3.5);
    const AutoExposureParams back = parseAe(autoExposureToJson(p));
    EXPECT_EQ(autoExposureToJson(back), autoExposureToJson(p));
    auto message = [&](const nlohmann::json& ae) { return test::errorOf([&] { parseAe(ae); }); };
    EXPECT_EQ(message({{"target_grey", 0}}),
              "scene.json: 'camera.sensor.auto_exposure.target_grey' must be between 0.0001 and 100 (got 0)");
    EXPECT_EQ(message({{"time_constant_s", -1}}),
              "scene.json: 'camera.sensor.auto_exposure.time_constant_s' must be between 0 and 60 (got -1)");
    EXPECT_EQ(message({{"min_ev", 2}, {"max_ev", 1}}),
              "scene.json: 'camera.sensor.auto_exposure.min_ev' must not be above 'max_ev'");
    EXPECT_EQ(message({{"speed", 1}}), "scene.json: unknown key 'camera.sensor.auto_exposure.speed'");
    EXPECT_EQ(message(0.5), "scene.json: 'camera.sensor.auto_exposure' must be an object");
}

TEST(AutoExposure, MaxWindowFramesBoundsTheWindowAndIsWrittenBackOnlyWhenSet) {
    AutoExposureParams p{.enabled = true, .timeConstantSeconds = 2.0};
    EXPECT_EQ(autoExposureWindow(p, 0.1), 100u); // ceil(5 tau / dt)
    EXPECT_FALSE(autoExposureToJson(p).contains("max_window_frames"));
    p.maxWindowFrames = 30;
    EXPECT_EQ(autoExposureWindow(p, 0.1), 30u);
    EXPECT_EQ(autoExposureWindow(p, 1.0), 10u); // a bound above 5 tau / dt changes nothing
    // The factor of a frame depends on its 30 frames before only: a meter 31 frames back changes nothing.
    std::vector<double> meters(40, 0.1), older = meters;
    older[40 - 32] = 10.0;
    EXPECT_EQ(autoExposureFactor(p, 0.1, meters), autoExposureFactor(p, 0.1, older));
    older[40 - 31] = 10.0;
    EXPECT_NE(autoExposureFactor(p, 0.1, meters), autoExposureFactor(p, 0.1, older));
    const nlohmann::json sensor = {{"auto_exposure", autoExposureToJson(p)}};
    JsonReader r(sensor, "scene.json", "camera.sensor");
    EXPECT_EQ(parseAutoExposure(r).maxWindowFrames, 30u);
    const nlohmann::json bad = {{"auto_exposure", {{"max_window_frames", 0}}}};
    JsonReader b(bad, "scene.json", "camera.sensor");
    try {
        parseAutoExposure(b);
        FAIL() << "max_window_frames 0 accepted";
    } catch (const Error& e) {
        EXPECT_EQ(
            std::string(e.what()),
            "scene.json: 'camera.sensor.auto_exposure.max_window_frames' must be an integer in [1, 100000] (got 0)");
    }
}
