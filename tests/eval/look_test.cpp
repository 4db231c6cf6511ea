// The realism statistics (eval/look_statistics.h) on analytic images whose values are known in closed form, the
// regions of a semantic image, and `sward-eval look` end to end on a tiny synthetic dataset.
#include "eval/look.h"
#include "eval/look_regions.h"
#include "eval/look_statistics.h"

#include "common/error.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sys/wait.h>
#include <unistd.h>

using namespace sward;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;

// Counter-based hash (splitmix64): the same numbers on every platform and thread count.
uint64_t hash64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}
double uniform(uint64_t counter) { // (0, 1)
    return (double(hash64(counter) >> 11) + 0.5) / double(uint64_t(1) << 53);
}
double gaussian(uint64_t counter) { // Box-Muller on two hashed uniforms
    return std::sqrt(-2 * std::log(uniform(2 * counter))) * std::cos(2 * kPi * uniform(2 * counter + 1));
}

cv::Mat full(cv::Size size) {
    return cv::Mat(size, CV_8U, cv::Scalar(255));
}

// A float BGR image with the grey value in every channel (grey = luma of equal channels).
cv::Mat greyToBgr(const cv::Mat& grey) {
    cv::Mat bgr;
    cv::merge(std::vector<cv::Mat>{grey, grey, grey}, bgr);
    return bgr;
}

cv::Mat whiteNoise(int size, double mean, double sigma, uint64_t seed) {
    cv::Mat grey(size, size, CV_32F);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            grey.at<float>(y, x) = float(mean + sigma * gaussian(seed * 1000003 + uint64_t(y * size + x)));
    return grey;
}

// Amplitude 1 / f (power 1 / f^2) at every frequency but 0, hashed phases: the real part of the inverse DFT,
// scaled to mean 0.5 and std 0.1.
cv::Mat oneOverF(int size) {
    cv::Mat spectrum(size, size, CV_64FC2);
    for (int v = 0; v < size; ++v)
        for (int u = 0; u < size; ++u) {
            const int fx = u <= size / 2 ? u : u - size, fy = v <= size / 2 ? v : v - size;
            const double f = std::hypot(double(fx), double(fy)) / size;
            const double phase = 2 * kPi * uniform(uint64_t(v * size + u) + 77);
            const double a = f > 0 ? 1 / f : 0;
            spectrum.at<cv::Vec2d>(v, u) = {a * std::cos(phase), a * std::sin(phase)};
        }
    cv::Mat complexImage, planes[2];
    cv::dft(spectrum, complexImage, cv::DFT_INVERSE);
    cv::split(complexImage, planes);
    cv::Scalar mean, std;
    cv::meanStdDev(planes[0], mean, std);
    cv::Mat grey;
    planes[0].convertTo(grey, CV_32F, 0.1 / std[0], 0.5 - 0.1 * mean[0] / std[0]);
    return grey;
}

// The std of grey - Gauss(sigma 1) for white noise of std 1: sqrt(sum over the kernel of (delta - K)^2).
double highPassFactor() {
    const cv::Mat g = cv::getGaussianKernel(7, 1, CV_64F);
    double sum = 0;
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 7; ++x) {
            const double k = g.at<double>(y) * g.at<double>(x);
            const double d = (x == 3 && y == 3 ? 1.0 : 0.0) - k;
            sum += d * d;
        }
    return std::sqrt(sum);
}

} // namespace

// ---- analytic images ----

TEST(LookFlat, EveryGradientLaplacianAndNoiseIsExactlyZero) {
    const cv::Mat bgr(128, 128, CV_8UC3, cv::Scalar(100, 120, 140));
    const LookStatistics s = measureRegion(prepareLookImage(bgr), full(bgr.size()));
    EXPECT_EQ(s.pixels, 128u * 128u);
    EXPECT_EQ(s.greyStd, 0.0);
    EXPECT_EQ(s.valueStd, 0.0);
    EXPECT_EQ(s.gradientMean, 0.0);
    EXPECT_EQ(s.gradientP99, 0.0);
    for (double level : s.laplacianRms) EXPECT_EQ(level, 0.0);
    EXPECT_EQ(s.sharpFraction, 0.0);
    EXPECT_EQ(s.noiseFloor, 0.0);
    EXPECT_EQ(s.noiseBlocks, 64u);
}

TEST(LookFlat, HasNoKeypoints) {
    const cv::Mat bgr(128, 128, CV_8UC3, cv::Scalar(100, 120, 140));
    const LookStatistics s = measureRegion(prepareLookImage(bgr), full(bgr.size()));
    for (double perMegapixel : s.keypointsPerMegapixel) EXPECT_EQ(perMegapixel, 0.0);
}

TEST(LookFlat, HasNoKurtosisAndNoSpectrumSlope) {
    const cv::Mat bgr(128, 128, CV_8UC3, cv::Scalar(100, 120, 140));
    const LookStatistics s = measureRegion(prepareLookImage(bgr, false), full(bgr.size()));
    EXPECT_TRUE(std::isnan(s.dxKurtosis));    // d/dx constant: kurtosis undefined
    EXPECT_EQ(s.spectrumWindows, 9u);         // (128 - 64) / 32 + 1 = 3 per side
    EXPECT_TRUE(std::isnan(s.spectrumSlope)); // zero power everywhere: nothing to fit
}

TEST(LookGradient, HorizontalRampHasItsSlopeAsGradientMeanAndP99) {
    const double slope = 0.002; // grey per pixel
    cv::Mat grey(96, 200, CV_32F);
    for (int y = 0; y < grey.rows; ++y)
        for (int x = 0; x < grey.cols; ++x) grey.at<float>(y, x) = float(0.25 + slope * x);
    const LookStatistics s = measureRegion(prepareLookImage(greyToBgr(grey), false), full(grey.size()));
    EXPECT_NEAR(s.gradientMean, slope, 0.02 * slope);
    EXPECT_NEAR(s.gradientP99, slope, 0.02 * slope);
    EXPECT_TRUE(std::isnan(s.dxKurtosis)); // d/dx is the constant slope
    EXPECT_NEAR(s.greyMean, 0.25 + slope * 99.5, 1e-6);
}

TEST(LookGradient, RegionMaskSelectsThePixelsMeasured) {
    cv::Mat grey(64, 128, CV_32F);
    for (int y = 0; y < grey.rows; ++y)
        for (int x = 0; x < grey.cols; ++x) grey.at<float>(y, x) = float(x < 64 ? 0.3 : 0.3 + 0.004 * (x - 64));
    cv::Mat left = cv::Mat::zeros(grey.size(), CV_8U), right = cv::Mat::zeros(grey.size(), CV_8U);
    left(cv::Rect(0, 0, 60, 64)).setTo(255);
    right(cv::Rect(68, 0, 60, 64)).setTo(255);
    const LookImage image = prepareLookImage(greyToBgr(grey), false);
    EXPECT_EQ(measureRegion(image, left).gradientMean, 0.0);
    EXPECT_NEAR(measureRegion(image, right).gradientMean, 0.004, 0.02 * 0.004);
    EXPECT_EQ(measureRegion(image, left).pixels, 60u * 64u);
}

TEST(LookNoise, WhiteNoiseGradientIsRayleighOfKnownScale) {
    const double sigma = 0.04;
    const LookStatistics s =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(256, 0.5, sigma, 1)), false), full({256, 256}));
    // Sobel / 8 d/dx and d/dy of white noise: independent normals of std sigma sqrt(12 / 64); the magnitude is
    // Rayleigh: mean scale sqrt(pi / 2), 99th percentile scale sqrt(-2 ln 0.01).
    const double scale = sigma * std::sqrt(12.0 / 64);
    EXPECT_NEAR(s.gradientMean, scale * std::sqrt(kPi / 2), 0.02 * scale * std::sqrt(kPi / 2));
    EXPECT_NEAR(s.gradientP99, scale * std::sqrt(-2 * std::log(0.01)), 0.02 * scale * std::sqrt(-2 * std::log(0.01)));
}

TEST(LookNoise, WhiteNoiseDxHasNoExcessKurtosis) {
    const LookStatistics s =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(256, 0.5, 0.04, 2)), false), full({256, 256}));
    EXPECT_NEAR(s.dxKurtosis, 0.0, 0.1); // the estimate's own spread for 65,000 pixels: sqrt(24 / n) = 0.02
}

TEST(LookNoise, WhiteNoiseSpectrumIsFlat) {
    const LookStatistics s =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(256, 0.5, 0.04, 3)), false), full({256, 256}));
    EXPECT_EQ(s.spectrumWindows, 49u); // 7 x 7 windows at stride 32
    // The fitted slopes of 49 windows of white noise spread by about 0.03 between seeds (20 seeds: all within
    // 0.061): 0 within 0.1.
    EXPECT_NEAR(s.spectrumSlope, 0.0, 0.1);
    EXPECT_NEAR(s.spectrumSlopeHigh, 0.0, 0.1);
    // The window is normalised so white noise of variance v has power v in every frequency cell.
    EXPECT_NEAR(s.spectrum[16], 0.04 * 0.04, 0.1 * 0.04 * 0.04);
}

TEST(LookNoise, NoiseFloorIsTheHighPassStdOfWhiteNoise) {
    const double sigma = 0.01;
    const LookStatistics s =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(256, 0.5, sigma, 4)), false), full({256, 256}));
    EXPECT_EQ(s.noiseBlocks, 256u);
    // 10th percentile of the std of 256 samples: about 1.28 standard errors (1 / sqrt(2 * 256)) below it (20
    // seeds: all within 1.6 %).
    const double expected = sigma * highPassFactor() * (1 - 1.2816 / std::sqrt(2.0 * 256));
    EXPECT_NEAR(s.noiseFloor, expected, 0.02 * expected);
}

TEST(LookNoise, SharpTextureFractionSeparatesStrongFromWeakNoise) {
    // High-pass std = sigma * 0.85: 0.034 is well above the 0.02 threshold, 0.0085 well below.
    const LookStatistics strong =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(128, 0.5, 0.04, 5)), false), full({128, 128}));
    const LookStatistics weak =
        measureRegion(prepareLookImage(greyToBgr(whiteNoise(128, 0.5, 0.01, 6)), false), full({128, 128}));
    EXPECT_EQ(strong.sharpFraction, 1.0);
    EXPECT_EQ(weak.sharpFraction, 0.0);
}

TEST(LookNoise, AFlatRegionBesideStrongTextureIsSmooth) {
    // The texture statistics see the region alone: the noise next to it leaks into neither test.
    cv::Mat grey = whiteNoise(128, 0.5, 0.1, 7);
    grey.colRange(64, 128).setTo(0.4);
    cv::Mat flat = cv::Mat::zeros(grey.size(), CV_8U);
    flat.colRange(64, 128).setTo(255);
    const LookStatistics s = measureRegion(prepareLookImage(greyToBgr(grey), false), flat);
    EXPECT_EQ(s.sharpFraction, 0.0);
    EXPECT_EQ(s.noiseBlocks, 32u);
    EXPECT_NEAR(s.noiseFloor, 0.0, 1e-6);
}

TEST(LookSpectrum, OneOverFImageHasPowerSlopeMinusTwo) {
    const LookStatistics s = measureRegion(prepareLookImage(greyToBgr(oneOverF(256)), false), full({256, 256}));
    EXPECT_NEAR(s.spectrumSlope, -2.0, 0.04);
    EXPECT_NEAR(s.spectrumSlopeHigh, -2.0, 0.04);
}

TEST(LookSpectrum, NoWindowFitsASmallRegion) {
    cv::Mat mask = cv::Mat::zeros(256, 256, CV_8U);
    mask(cv::Rect(10, 10, 63, 200)).setTo(255); // 63 px wide: no 64 px window
    const LookStatistics s = measureRegion(prepareLookImage(greyToBgr(oneOverF(256)), false), mask);
    EXPECT_EQ(s.spectrumWindows, 0u);
    EXPECT_TRUE(std::isnan(s.spectrumSlope));
    EXPECT_TRUE(std::isnan(s.spectrumSlopeHigh));
}

TEST(LookSpectrum, SlopeFitsAKnownPowerLaw) {
    std::vector<double> spectrum(33);
    for (size_t k = 0; k < spectrum.size(); ++k) spectrum[k] = 5 * std::pow(double(k) / 64, -3.0);
    EXPECT_NEAR(spectrumSlope(spectrum, 2.0 / 64, 0.4), -3.0, 1e-9);
    EXPECT_NEAR(spectrumSlope(spectrum, 0.1, 0.4), -3.0, 1e-9);
}

TEST(LookColour, SaturatedPatchHasExactSaturationAndNoHueSpread) {
    const cv::Mat bgr(64, 64, CV_8UC3, cv::Scalar(40, 200, 120)); // max 200, min 40: saturation 0.8
    const LookStatistics s = measureRegion(prepareLookImage(bgr, false), full(bgr.size()));
    EXPECT_NEAR(s.saturationMean, 0.8, 1e-12);
    EXPECT_NEAR(s.hueStdDegrees, 0.0, 1e-5);
    EXPECT_EQ(s.valueStd, 0.0);
}

TEST(LookColour, TwoHuesAQuarterTurnApartHaveTheCircularStdOfTheirResultant) {
    cv::Mat bgr(64, 64, CV_8UC3, cv::Scalar(0, 0, 255));        // red: hue 0
    bgr(cv::Rect(0, 0, 32, 64)).setTo(cv::Scalar(0, 255, 128)); // R 128, G 255, B 0: hue 89.9
    const LookStatistics s = measureRegion(prepareLookImage(bgr, false), full(bgr.size()));
    // Hue of (R 128, G 255, B 0): 60 * (B - R) / (max - min) + 120 = 60 * -128 / 255 + 120.
    const double h = (60.0 * -128 / 255 + 120) * kPi / 180;
    const double r = std::hypot(1 + std::cos(h), std::sin(h)) / 2; // equal weights (saturation 1)
    EXPECT_NEAR(s.hueStdDegrees, std::sqrt(-2 * std::log(r)) * 180 / kPi, 1e-9);
    EXPECT_NEAR(s.saturationMean, 1.0, 1e-12);
    EXPECT_NEAR(s.valueStd, 0.0, 1e-12); // both have max 255
}

TEST(LookColour, GreyPixelsHaveNoHueSpread) {
    const cv::Mat bgr(32, 32, CV_8UC3, cv::Scalar(90, 90, 90));
    const LookStatistics s = measureRegion(prepareLookImage(bgr, false), full(bgr.size()));
    EXPECT_EQ(s.saturationMean, 0.0);
    EXPECT_TRUE(std::isnan(s.hueStdDegrees)); // no saturation: hue undefined
}

TEST(LookKeypoints, ARegionThinnerThanTheErosionHasNone) {
    const cv::Mat bgr(128, 128, CV_8UC3, cv::Scalar(100, 120, 140));
    cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
    mask(cv::Rect(20, 20, 16, 80)).setTo(255); // 16 px wide: eroded by 8 px on each side, nothing left
    const LookStatistics s = measureRegion(prepareLookImage(bgr), mask);
    EXPECT_EQ(s.erodedPixels, 0u);
    for (double perMegapixel : s.keypointsPerMegapixel) EXPECT_TRUE(std::isnan(perMegapixel));
}

TEST(LookKeypoints, CornersOfSquaresAreCountedPerMegapixelOfTheErodedRegion) {
    cv::Mat bgr(128, 128, CV_8UC3, cv::Scalar(40, 40, 40));
    for (int y = 16; y < 128; y += 32)
        for (int x = 16; x < 128; x += 32) bgr(cv::Rect(x - 6, y - 6, 12, 12)).setTo(cv::Scalar(220, 220, 220));
    // Blurred, so neighbouring pixels of a corner score differently and non-max suppression keeps one of them.
    cv::GaussianBlur(bgr, bgr, cv::Size(5, 5), 1.0);
    const LookImage image = prepareLookImage(bgr);
    const LookStatistics s = measureRegion(image, full(bgr.size()));
    EXPECT_EQ(s.erodedPixels, 112u * 112u);    // the frame's border erodes the region by 8 px
    ASSERT_EQ(image.keypoints[2].size(), 64u); // FAST: each corner of the 16 squares once
    EXPECT_DOUBLE_EQ(s.keypointsPerMegapixel[2], 64 / (112 * 112 * 1e-6)); // all inside the eroded region
}

TEST(LookStatistics, PercentileInterpolatesBetweenOrderStatistics) {
    EXPECT_EQ(percentileOf({4, 1, 3, 2}, 0.5), 2.5);
    EXPECT_EQ(percentileOf({4, 1, 3, 2}, 0.0), 1.0);
    EXPECT_EQ(percentileOf({4, 1, 3, 2}, 1.0), 4.0);
    EXPECT_TRUE(std::isnan(percentileOf({}, 0.5)));
}

// ---- regions ----

namespace {

// Rows 0-19 sky, then ground; a vegetation block, a turf block, a track block and an object.
cv::Mat syntheticSemantic() {
    cv::Mat semantic(100, 80, CV_8U, cv::Scalar(1)); // ground
    semantic(cv::Rect(0, 0, 80, 20)).setTo(0);       // sky
    semantic(cv::Rect(0, 30, 20, 20)).setTo(2);      // vegetation category 0
    semantic(cv::Rect(20, 30, 20, 20)).setTo(11);    // turf
    semantic(cv::Rect(40, 30, 20, 20)).setTo(12);    // track
    semantic(cv::Rect(60, 20, 20, 5)).setTo(8);      // object at the top of the ground
    return semantic;
}

} // namespace

TEST(LookRegions, SwardRegionsFollowTheSemanticClasses) {
    const std::vector<LookRegion> regions = swardRegions(syntheticSemantic());
    ASSERT_EQ(regions.size(), 5u);
    EXPECT_EQ(regions[0].name, "all");
    EXPECT_EQ(cv::countNonZero(regions[0].mask), 80 * 80); // every non-sky pixel, the object too
    EXPECT_EQ(regions[1].name, "vegetation");
    EXPECT_EQ(cv::countNonZero(regions[1].mask), 2 * 20 * 20); // category 0 and turf
    EXPECT_EQ(regions[2].name, "soil");
    EXPECT_EQ(cv::countNonZero(regions[2].mask), 80 * 80 - 2 * 400 - 100); // ground and track, not the object
    EXPECT_EQ(regions[3].name, "turf");
    EXPECT_EQ(cv::countNonZero(regions[3].mask), 400);
}

TEST(LookRegions, FarBandIsEightPercentOfTheHeightBelowTheTopOfTheGround) {
    const std::vector<LookRegion> regions = swardRegions(syntheticSemantic());
    EXPECT_EQ(regions[4].name, "far");
    // Rows 20 .. 27 (8 % of 100 rows), without the object's 20 x 5 pixels.
    EXPECT_EQ(cv::countNonZero(regions[4].mask), 8 * 80 - 100);
    EXPECT_EQ(cv::countNonZero(regions[4].mask.rowRange(0, 20)), 0);
    EXPECT_EQ(cv::countNonZero(regions[4].mask.rowRange(28, 100)), 0);
}

TEST(LookRegions, AllSkyFrameHasEmptyRegions) {
    for (const LookRegion& region : swardRegions(cv::Mat::zeros(40, 40, CV_8U)))
        EXPECT_EQ(cv::countNonZero(region.mask), 0) << region.name;
}

TEST(LookRegions, ReferenceRegionsFromRectanglesAndMasks) {
    const fs::path dir = test::tempDir();
    cv::imwrite((dir / "a.png").string(), cv::Mat(40, 60, CV_8UC3, cv::Scalar(10, 20, 30)));
    cv::imwrite((dir / "b.jpg").string(), cv::Mat(30, 30, CV_8UC3, cv::Scalar(10, 20, 30)));
    cv::Mat mask = cv::Mat::zeros(40, 60, CV_8U);
    mask(cv::Rect(0, 0, 10, 10)).setTo(1);
    cv::imwrite((dir / "a_soil.png").string(), mask);
    std::ofstream(dir / "regions.json")
        << R"({"a.png": {"soil": "a_soil.png", "vegetation": [[50, 30, 20, 20], [0, 0, 2, 2]]}})";
    const std::vector<ReferenceImage> images = readReferenceImages(dir.string());
    ASSERT_EQ(images.size(), 3u); // a.png, a_soil.png (an image too: it has no entry) and b.jpg
    EXPECT_EQ(images[0].file, "a.png");
    ASSERT_EQ(images[0].regions.size(), 2u);
    EXPECT_EQ(images[0].regions[0].name, "soil");
    EXPECT_EQ(cv::countNonZero(images[0].regions[0].mask), 100);
    EXPECT_EQ(images[0].regions[1].name, "vegetation");
    EXPECT_EQ(cv::countNonZero(images[0].regions[1].mask), 10 * 10 + 4); // clipped to the image
    EXPECT_EQ(images[2].file, "b.jpg");
    ASSERT_EQ(images[2].regions.size(), 1u);
    EXPECT_EQ(images[2].regions[0].name, "all");
    EXPECT_EQ(cv::countNonZero(images[2].regions[0].mask), 900);
}

TEST(LookRegions, ReferencePathsMayNotLeaveTheFolder) {
    const fs::path dir = test::tempDir();
    fs::create_directories(dir / "ref");
    cv::imwrite((dir / "ref" / "a.png").string(), cv::Mat(20, 20, CV_8UC3, cv::Scalar(1, 2, 3)));
    cv::imwrite((dir / "outside.png").string(), cv::Mat(20, 20, CV_8U, cv::Scalar(255)));
    std::ofstream(dir / "ref" / "regions.json") << R"({"a.png": {"soil": "../outside.png"}})";
    test::expectError([&] { readReferenceImages((dir / "ref").string()); }, {"../outside.png", "not a file name"});
    fs::create_symlink(dir / "outside.png", dir / "ref" / "link.png");
    std::ofstream(dir / "ref" / "regions.json") << R"({"a.png": {"soil": "link.png"}})";
    test::expectError([&] { readReferenceImages((dir / "ref").string()); },
                      {"link.png", "out of the reference folder"});
}

TEST(LookRegions, BadRegionsFileIsOneClearError) {
    const fs::path dir = test::tempDir();
    cv::imwrite((dir / "a.png").string(), cv::Mat(20, 30, CV_8UC3, cv::Scalar(1, 2, 3)));
    cv::imwrite((dir / "small.png").string(), cv::Mat(10, 10, CV_8U, cv::Scalar(255)));
    const std::pair<const char*, const char*> cases[] = {
        {R"({"a.png": )", "not valid JSON"},
        {R"({"b.png": {"soil": [[0, 0, 5, 5]]}})", "'b.png' is no image of the folder"},
        {R"({"a.png": {"soil": [[0, 0, 5]]}})", "a crop rectangle is [x, y, w, h]"},
        {R"({"a.png": {"soil": [[0, 0, 0, 5]]}})", "positive width and height"},
        {R"({"a.png": {"soil": "small.png"}})", "the region mask is 10x10, its image 30x20"},
        {R"({"a.png": {"soil": "missing.png"}})", "missing.png"},
        {R"({"a.png": {"soil": 3}})", "expected crop rectangles or a mask file name"},
    };
    for (const auto& [text, message] : cases) {
        std::ofstream(dir / "regions.json") << text;
        test::expectError([&] { readReferenceImages(dir.string()); }, {message});
    }
}

TEST(LookRegions, AFolderWithoutImagesIsOneClearError) {
    const fs::path dir = test::tempDir();
    std::ofstream(dir / "notes.txt") << "no image";
    test::expectError([&] { readReferenceImages(dir.string()); }, {"holds no image"});
}

TEST(LookRegions, MissingReferenceFolderIsOneClearError) {
    test::expectError([] { readReferenceImages("/nonexistent/sward-look-reference"); },
                      {"reference folder '/nonexistent/sward-look-reference' does not exist"});
}

TEST(LookSummary, GapIsInUnitsOfTheRealInterquartileRange) {
    LookSummary sward, real;
    sward.median = {5};
    real.median = {2};
    real.q1 = {1};
    real.q3 = {3};
    real.std = {10};
    EXPECT_EQ(lookGap(sward, real, 0), 1.5);
    real.q1 = real.q3 = {2}; // no IQR: the std
    EXPECT_EQ(lookGap(sward, real, 0), 0.3);
    real.std = {0};
    EXPECT_TRUE(std::isnan(lookGap(sward, real, 0)));
}

// ---- sward-eval look end to end ----

namespace {

struct RunResult {
    int exitCode = -1;
    std::string err;
};

RunResult runLookTool(const std::string& args) {
    const fs::path errFile = fs::temp_directory_path() / ("sward_look_err_" + std::to_string(::getpid()) + ".txt");
    const std::string command = std::string(SWARD_EVAL_EXE) + " look " + args + " >/dev/null 2>" + errFile.string();
    const int status = std::system(command.c_str());
    RunResult result{WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::readText(errFile)};
    fs::remove(errFile);
    return result;
}

// Three 128x96 frames: hashed noise over a ramp, sky at the top, vegetation and soil halves.
fs::path writeTinyDataset(const fs::path& root) {
    const fs::path dir = root / "dataset";
    fs::create_directories(dir / "preview");
    fs::create_directories(dir / "semantic");
    for (uint32_t frame = 0; frame < 3; ++frame) {
        cv::Mat bgr(96, 128, CV_8UC3), semantic(96, 128, CV_8U);
        for (int y = 0; y < 96; ++y)
            for (int x = 0; x < 128; ++x) {
                const double n = uniform(uint64_t(frame) << 32 | uint64_t(y * 128 + x));
                const int level = int(60 + x / 2 + 60 * n);
                bgr.at<cv::Vec3b>(y, x) = {uint8_t(level / 2), uint8_t(level), uint8_t(level * 3 / 4)};
                semantic.at<uint8_t>(y, x) = y < 16 ? 0 : x < 64 ? 2 : 1;
            }
        char name[16];
        std::snprintf(name, sizeof name, "%06u.png", frame);
        cv::imwrite((dir / "preview" / name).string(), bgr);
        cv::imwrite((dir / "semantic" / name).string(), semantic);
    }
    return dir;
}

} // namespace

TEST(LookTool, OneAndTwoThreadsWriteBitwiseIdenticalFiles) {
    const fs::path root = test::tempDir();
    const fs::path dir = writeTinyDataset(root);
    fs::create_directories(root / "real");
    cv::imwrite((root / "real" / "photo.png").string(), cv::imread((dir / "preview" / "000001.png").string()));
    for (const char* threads : {"1", "2"}) {
        const RunResult r = runLookTool("'" + dir.string() + "' --reference '" + (root / "real").string() +
                                        "' --out '" + (root / threads).string() + "' --threads " + threads);
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    for (const char* file : {"look.json", "look.csv", "report.md", "look_soil.png"}) {
        const std::string one = test::readText(root / "1" / file);
        EXPECT_FALSE(one.empty()) << file;
        EXPECT_EQ(one, test::readText(root / "2" / file)) << file;
    }
}

TEST(LookTool, JsonHoldsEveryFrameRegionAndTheGap) {
    const fs::path root = test::tempDir();
    const fs::path dir = writeTinyDataset(root);
    // The reference: frames 1 and 2 themselves, region "all" their non-sky rows: every median is sward's own.
    fs::create_directories(root / "real");
    for (const char* frame : {"000001", "000002"})
        fs::copy_file(dir / "preview" / (std::string(frame) + ".png"), root / "real" / (std::string(frame) + ".png"));
    std::ofstream(root / "real" / "regions.json")
        << R"({"000001.png": {"all": [[0, 16, 128, 80]]}, "000002.png": {"all": [[0, 16, 128, 80]]}})";
    const RunResult r =
        runLookTool("'" + dir.string() + "' --reference '" + (root / "real").string() + "' --frames 1:3 --no-pictures");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(test::readText(dir / "eval-look" / "look.json"));
    ASSERT_EQ(j["frames"].size(), 2u);
    EXPECT_EQ(j["frames"][0]["frame"], "000001");
    EXPECT_EQ(j["frames"][0]["regions"]["soil"]["pixels"], 64 * 80);
    EXPECT_EQ(j["frames"][0]["regions"]["all"]["pixels"], 128 * 80);
    EXPECT_TRUE(j["frames"][0]["regions"]["far"]["spectrum_slope"].is_null()); // 8 rows: no 64 px window
    EXPECT_EQ(j["summary"]["all"]["images"], 2);
    EXPECT_EQ(j["reference_images"][1]["file"], "000002.png");
    EXPECT_EQ(j["summary"]["all"], j["reference_summary"]["all"]);
    ASSERT_TRUE(j["gap"]["all"]["gradient_mean"].is_number());
    for (const auto& [key, gap] : j["gap"]["all"].items())
        EXPECT_TRUE(gap.is_null() || gap.get<double>() == 0.0) << key << " " << gap;
    EXPECT_FALSE(j["gap"].contains("soil")); // the reference has no soil region
    EXPECT_FALSE(fs::exists(dir / "eval-look" / "look_all.png"));
}

TEST(LookTool, SmoothTurfIsTheShareOfNonSkyPixelsOfTurfWithoutSharpTexture) {
    // Frame 0: flat, all turf below the sky: every turf pixel is smooth. Frame 1: strong noise, all turf: none is.
    const fs::path dir = test::tempDir() / "dataset";
    fs::create_directories(dir / "preview");
    fs::create_directories(dir / "semantic");
    cv::Mat semantic(64, 64, CV_8U, cv::Scalar(11));
    semantic.rowRange(0, 16).setTo(0);
    cv::Mat noisy(64, 64, CV_8UC3);
    for (int i = 0; i < 64 * 64; ++i)
        noisy.at<cv::Vec3b>(i / 64, i % 64) = cv::Vec3b::all(uint8_t(255 * uniform(uint64_t(i))));
    cv::imwrite((dir / "preview" / "000000.png").string(), cv::Mat(64, 64, CV_8UC3, cv::Scalar(40, 90, 60)));
    cv::imwrite((dir / "preview" / "000001.png").string(), noisy);
    for (const char* name : {"000000.png", "000001.png"}) cv::imwrite((dir / "semantic" / name).string(), semantic);
    const RunResult r = runLookTool("'" + dir.string() + "' --no-pictures");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(test::readText(dir / "eval-look" / "look.json"));
    EXPECT_EQ(j["frames"][0]["smooth_turf_share"], 1.0);
    EXPECT_EQ(j["frames"][1]["smooth_turf_share"], 0.0);
    EXPECT_EQ(j["smooth_turf_share"], 0.5); // the median
}

TEST(LookTool, MissingPreviewIsOneClearError) {
    const fs::path root = test::tempDir();
    const fs::path dir = writeTinyDataset(root);
    fs::remove_all(dir / "preview");
    const RunResult r = runLookTool("'" + dir.string() + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("sward-eval: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("preview"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "eval-look"));
}

TEST(LookTool, MissingReferenceFolderIsOneClearError) {
    const fs::path root = test::tempDir();
    const fs::path dir = writeTinyDataset(root);
    const RunResult r = runLookTool("'" + dir.string() + "' --reference '" + (root / "nothing").string() + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("sward-eval: error: reference folder '" + (root / "nothing").string() + "' does not exist"),
              std::string::npos)
        << r.err;
}
