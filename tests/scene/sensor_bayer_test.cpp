// A single-chip Bayer sensor (scene/sensor_bayer.h): the mosaic, its per-photosite noise, the two demosaicing
// methods (against OpenCV's), the false colour they leave at fine detail, and the keys' parse and write-back.
#include "scene/sensor_bayer.h"
#include "scene/sensor_model.h"
#include "scene/sensor_raw.h"

#include "common/error.h"
#include "common/hash.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace sward;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;
constexpr BayerPattern kPatterns[] = {BayerPattern::Rggb, BayerPattern::Bggr, BayerPattern::Grbg, BayerPattern::Gbrg};
constexpr Demosaic kMethods[] = {Demosaic::Bilinear, Demosaic::Malvar};

Intrinsics testCamera() {
    return {60.0, 60.0, 32.0, 24.0, kWidth, kHeight};
}

SensorParams bayerSensor(BayerPattern pattern, Demosaic method = Demosaic::Bilinear) {
    SensorParams p;
    p.enabled = true;
    p.cfa = {pattern, method};
    return p;
}

std::vector<float> colourField(float r, float g, float b) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
        rgba[p * 4 + 0] = r;
        rgba[p * 4 + 1] = g;
        rgba[p * 4 + 2] = b;
        rgba[p * 4 + 3] = 1.0f;
    }
    return rgba;
}

// A grey image whose value at (x, y) is `grey(x, y)`: any colour the demosaicing gives it is false colour.
template <class F> std::vector<float> greyImage(F grey) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            float* px = &rgba[(size_t(y) * kWidth + x) * 4];
            px[0] = px[1] = px[2] = grey(x, y);
            px[3] = 1.0f;
        }
    return rgba;
}

// Mean of max(R, G, B) - min(R, G, B) over pixels at least 4 from the border.
double meanChroma(const std::vector<float>& rgba) {
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t y = 4; y + 4 < kHeight; ++y)
        for (uint32_t x = 4; x + 4 < kWidth; ++x, ++n) {
            const float* px = &rgba[(size_t(y) * kWidth + x) * 4];
            sum += std::max({px[0], px[1], px[2]}) - std::min({px[0], px[1], px[2]});
        }
    return sum / double(n);
}

bool bitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

SensorParams parse(const nlohmann::json& j) {
    return parseSensor(j, "scene.json", "camera.sensor");
}

} // namespace

TEST(SensorBayer, PatternsNameTheTileInReadingOrder) {
    EXPECT_EQ(bayerChannel(BayerPattern::Rggb, 0, 0), 0u);
    EXPECT_EQ(bayerChannel(BayerPattern::Rggb, 1, 0), 1u);
    EXPECT_EQ(bayerChannel(BayerPattern::Rggb, 0, 1), 1u);
    EXPECT_EQ(bayerChannel(BayerPattern::Rggb, 3, 5), 2u);
    EXPECT_EQ(bayerChannel(BayerPattern::Bggr, 0, 0), 2u);
    EXPECT_EQ(bayerChannel(BayerPattern::Bggr, 1, 1), 0u);
    EXPECT_EQ(bayerChannel(BayerPattern::Grbg, 1, 0), 0u);
    EXPECT_EQ(bayerChannel(BayerPattern::Grbg, 0, 1), 2u);
    EXPECT_EQ(bayerChannel(BayerPattern::Gbrg, 1, 0), 2u);
    EXPECT_EQ(bayerChannel(BayerPattern::Gbrg, 0, 1), 0u);
    EXPECT_EQ(bayerChannel(BayerPattern::Gbrg, 2, 2), 1u);
}

// Every pattern and method gives a constant colour back bit for bit, borders included (the kernels' weights sum to
// one and the sums are exact).
TEST(SensorBayer, AConstantColourFieldDemosaicsBackExactly) {
    const std::vector<float> field = colourField(0.3f, 0.55f, 0.1234567f);
    for (BayerPattern pattern : kPatterns)
        for (Demosaic method : kMethods) {
            std::vector<float> image = field;
            applySensor(bayerSensor(pattern, method), testCamera(), 7, 3, 0, image);
            EXPECT_TRUE(bitwiseEqual(image, field)) << bayerPatternName(pattern) << " " << int(method);
        }
}

// cv::demosaicing's bilinear COLOR_Bayer??2BGR on a random 16-bit mosaic (values multiples of 4, so the means of 2 or
// 4 are whole and OpenCV's rounding drops nothing) equals ours at every pixel off the border. OpenCV names a
// pattern by the second row's second and third pixels: RGGB (R G / G B) is its BayerBG.
TEST(SensorBayer, BilinearEqualsOpenCvDemosaicing) {
    const std::pair<BayerPattern, int> codes[] = {{BayerPattern::Rggb, cv::COLOR_BayerBG2BGR},
                                                  {BayerPattern::Bggr, cv::COLOR_BayerRG2BGR},
                                                  {BayerPattern::Grbg, cv::COLOR_BayerGB2BGR},
                                                  {BayerPattern::Gbrg, cv::COLOR_BayerGR2BGR}};
    cv::Mat mosaic(int(kHeight), int(kWidth), CV_16UC1);
    for (int y = 0; y < mosaic.rows; ++y)
        for (int x = 0; x < mosaic.cols; ++x)
            mosaic.at<uint16_t>(y, x) = uint16_t(4 * (hashKey({0xba7e5ull, uint64_t(x), uint64_t(y)}) % 16000));
    for (const auto& [pattern, code] : codes) {
        std::vector<float> rgba(size_t(kWidth) * kHeight * 4, -1.0f); // the channels a photosite lacks: overwritten
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x)
                rgba[(size_t(y) * kWidth + x) * 4 + bayerChannel(pattern, x, y)] = mosaic.at<uint16_t>(int(y), int(x));
        demosaic({pattern, Demosaic::Bilinear}, kWidth, kHeight, rgba);
        cv::Mat bgr;
        cv::demosaicing(mosaic, bgr, code);
        size_t differing = 0;
        for (uint32_t y = 1; y + 1 < kHeight; ++y)
            for (uint32_t x = 1; x + 1 < kWidth; ++x)
                for (uint32_t c = 0; c < 3; ++c)
                    differing +=
                        rgba[(size_t(y) * kWidth + x) * 4 + c] != float(bgr.at<cv::Vec3w>(int(y), int(x))[2 - int(c)]);
        EXPECT_EQ(differing, 0u) << bayerPatternName(pattern);
    }
}

// Noise-free, each photosite keeps exactly its channel of the light (the red photosites hold the red channel); with
// noise, a photosite's value is bitwise the three-channel sensor's value of that channel (one gaussian per pixel,
// keyed by the photosite's channel), so the mosaic's noise has the shot + read model's moments per channel, and the
// interpolated channels, means of 2 or 4 independent photosites, have a half or a quarter of that variance.
TEST(SensorBayer, EachPhotositeHasItsOwnChannelsNoise) {
    std::vector<float> light(size_t(kWidth) * kHeight * 4);
    for (size_t i = 0; i < light.size(); ++i) light[i] = i % 4 == 3 ? 1.0f : float(i % 89) * 0.011f;
    std::vector<float> clean = light;
    applySensor(bayerSensor(BayerPattern::Grbg), testCamera(), 7, 3, 0, clean);
    EXPECT_EQ(bayerMosaic(BayerPattern::Grbg, kWidth, kHeight, clean),
              bayerMosaic(BayerPattern::Grbg, kWidth, kHeight, light));

    SensorParams noisy = bayerSensor(BayerPattern::Rggb);
    noisy.electronsPerUnit = 1000.0;
    noisy.readNoise = 5.0;
    SensorParams threeChannel = noisy;
    threeChannel.cfa = {};
    const float level[3] = {0.5f, 0.2f, 0.05f};
    const std::vector<float> field = colourField(level[0], level[1], level[2]);
    std::vector<float> bayer = field, rgb = field;
    applySensor(noisy, testCamera(), 7, 3, 0, bayer);
    applySensor(threeChannel, testCamera(), 7, 3, 0, rgb);
    EXPECT_EQ(bayerMosaic(BayerPattern::Rggb, kWidth, kHeight, bayer),
              bayerMosaic(BayerPattern::Rggb, kWidth, kHeight, rgb));

    double sum[3] = {}, sum2[3] = {}, count[3] = {}, greenAtRed = 0.0, greenAtRedCount = 0.0;
    for (uint32_t y = 2; y + 2 < kHeight; ++y)
        for (uint32_t x = 2; x + 2 < kWidth; ++x) {
            const uint32_t c = bayerChannel(BayerPattern::Rggb, x, y);
            const double v = bayer[(size_t(y) * kWidth + x) * 4 + c] - level[c];
            sum[c] += v;
            sum2[c] += v * v;
            ++count[c];
            if (c == 0) {
                const double g = bayer[(size_t(y) * kWidth + x) * 4 + 1] - level[1];
                greenAtRed += g * g;
                ++greenAtRedCount;
            }
        }
    for (uint32_t c = 0; c < 3; ++c) {
        const double variance = (level[c] * 1000.0 + 25.0) / 1e6;
        EXPECT_NEAR(sum[c] / count[c], 0.0, 5.0 * std::sqrt(variance / count[c])) << c;
        EXPECT_NEAR(sum2[c] / count[c] / variance, 1.0, 5.0 * std::sqrt(2.0 / count[c])) << c;
    }
    const double greenVariance = (level[1] * 1000.0 + 25.0) / 1e6;
    EXPECT_NEAR(greenAtRed / greenAtRedCount / (greenVariance / 4.0), 1.0, 5.0 * std::sqrt(2.0 / greenAtRedCount));
}

// Grey detail at the pixel scale, like grass blades, takes colour from the mosaic (a three-channel sensor has none):
// one-pixel lines every 3 pixels, diagonal ones, 2-pixel stripes. Bilinear demosaicing gives them a mean chroma
// (max - min of R, G, B) of 0.5-0.67 of the white; Malvar-He-Cutler, which corrects with the own channel's
// Laplacian, 0.13-0.46. Alternate one-pixel stripes (period 2, the Nyquist limit of each colour's photosites) are
// indistinguishable from a colour in the mosaic: both methods make them fully coloured, a real sensor's moire too.
TEST(SensorBayer, FineDetailGetsFalseColourMalvarLess) {
    auto chroma = [](Demosaic method, auto grey) {
        std::vector<float> image = greyImage(grey);
        demosaic({BayerPattern::Rggb, method}, kWidth, kHeight, image);
        return meanChroma(image);
    };
    auto stripes = [](uint32_t x, uint32_t) { return float(x % 2); };
    EXPECT_EQ(chroma(Demosaic::Bilinear, stripes), 1.0);
    EXPECT_EQ(chroma(Demosaic::Malvar, stripes), 1.0);
    auto lines = [](uint32_t x, uint32_t) { return float(x % 3 == 0); };
    auto diagonal = [](uint32_t x, uint32_t y) { return float((x + y) % 3 == 0); };
    auto wideStripes = [](uint32_t x, uint32_t) { return float(x / 2 % 2); };
    EXPECT_NEAR(chroma(Demosaic::Bilinear, lines), 0.661, 0.001);
    EXPECT_NEAR(chroma(Demosaic::Malvar, lines), 0.413, 0.001);
    EXPECT_NEAR(chroma(Demosaic::Bilinear, diagonal), 0.667, 0.001);
    EXPECT_NEAR(chroma(Demosaic::Malvar, diagonal), 0.458, 0.001);
    EXPECT_EQ(chroma(Demosaic::Bilinear, wideStripes), 0.5);
    EXPECT_EQ(chroma(Demosaic::Malvar, wideStripes), 0.125);
}

TEST(SensorBayer, SameInputsGiveTheSameBytes) {
    SensorParams p = bayerSensor(BayerPattern::Bggr, Demosaic::Malvar);
    p.electronsPerUnit = 500.0;
    p.readNoise = 3.0;
    p.bitDepth = 12;
    const std::vector<float> field =
        greyImage([](uint32_t x, uint32_t y) { return float((x * 7 + y * 3) % 11) * 0.08f; });
    std::vector<float> first = field, second = field, otherFrame = field;
    applySensor(p, testCamera(), 7, 3, 0, first);
    applySensor(p, testCamera(), 7, 3, 0, second);
    applySensor(p, testCamera(), 7, 4, 0, otherFrame);
    EXPECT_TRUE(bitwiseEqual(first, second));
    EXPECT_FALSE(bitwiseEqual(first, otherFrame));
    const std::vector<uint16_t> dn = rawDigitalImage(p, first, kWidth);
    ASSERT_EQ(dn.size(), size_t(kWidth) * kHeight); // one DN per photosite
    const std::vector<float> mosaic = bayerMosaic(BayerPattern::Bggr, kWidth, kHeight, first);
    for (size_t i = 0; i < dn.size(); ++i) ASSERT_EQ(dn[i], rawDigitalNumber(mosaic[i], 1.0, 12)) << i;
}

TEST(SensorBayer, KeysParseAndRoundTrip) {
    const SensorParams none = parse({{"exposure", 2}});
    EXPECT_FALSE(none.cfa.enabled());
    EXPECT_FALSE(sensorToJson(none).contains("bayer")); // a three-channel sensor's record as before
    EXPECT_EQ(sensorToJson(parse({{"exposure", 2}, {"bayer", nullptr}})), sensorToJson(none));
    const SensorParams p = parse({{"bayer", "GBRG"}, {"demosaic", "malvar"}});
    EXPECT_EQ(p.cfa.pattern, BayerPattern::Gbrg);
    EXPECT_EQ(p.cfa.demosaic, Demosaic::Malvar);
    const nlohmann::json written = sensorToJson(p);
    EXPECT_EQ(written.at("bayer"), "GBRG");
    EXPECT_EQ(written.at("demosaic"), "malvar");
    EXPECT_EQ(sensorToJson(parse(written)), written);
    EXPECT_EQ(parse({{"bayer", "RGGB"}}).cfa.demosaic, Demosaic::Bilinear);
}

TEST(SensorBayer, BadKeysAreRefusedNamingThem) {
    auto message = [](const nlohmann::json& j) { return test::errorOf([&] { parse(j); }); };
    EXPECT_NE(message({{"bayer", "RGBG"}}).find("'camera.sensor.bayer' must be null"), std::string::npos);
    EXPECT_NE(message({{"bayer", 1}}).find("'camera.sensor.bayer' must be null"), std::string::npos);
    EXPECT_NE(message({{"bayer", "rggb"}}).find("(got \"rggb\")"), std::string::npos);
    EXPECT_NE(
        message({{"bayer", "RGGB"}, {"demosaic", "ahd"}}).find("'camera.sensor.demosaic' must be bilinear or malvar"),
        std::string::npos);
    EXPECT_NE(message({{"demosaic", "malvar"}}).find("'camera.sensor.demosaic' needs a colour filter array"),
              std::string::npos);
    EXPECT_NE(message({{"enabled", false}, {"bayer", "RGGB"}}).find("'camera.sensor.bayer' needs an enabled sensor"),
              std::string::npos);
}
