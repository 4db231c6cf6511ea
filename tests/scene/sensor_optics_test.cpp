// The lens before the sensor (scene/sensor_optics.h) on analytic images: what stays sharp, how much is blurred and
// where the colours go, against the thin-lens and Gaussian formulas written out here.
#include "scene/sensor_optics.h"

#include "scene/sensor_model.h"

#include "common/error.h"
#include "common/half_float.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

using namespace sward;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr float kInf = std::numeric_limits<float>::infinity();

Intrinsics testCamera(double fx = 100.0) {
    return {fx, fx, 80.0, 60.0, kWidth, kHeight};
}

// A long lens (fx 1000 px, 5 mm with 5 um pixels) wide open at f/1, focused at 0.2 m: a plane at twice the focus
// distance has a circle of confusion of 12.8 pixels, so the blur is measured well clear of pixel quantisation.
constexpr double kLongFx = 1000.0;
constexpr float kFocus = 0.2f;

SensorParams wideOpen() {
    SensorParams p;
    p.enabled = true;
    p.optics.apertureF = 1.0;
    p.optics.pixelSizeUm = 5.0;
    p.optics.focusDistanceM = kFocus;
    return p;
}

// The thin-lens circle of confusion's diameter in pixels, written out from the lens equation.
double predictedCocPx(const SensorParams& p, double fx, double depth) {
    const double pitch = p.optics.pixelSizeUm * 1e-6, f = fx * pitch, a = f / p.optics.apertureF;
    const double s = p.optics.focusDistanceM;
    return a * f * std::abs(depth - s) / (depth * (s - f)) / pitch;
}

std::vector<float> texture() {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float((i * 2654435761u) % 1000u) / 500.0f;
    return rgba;
}

std::vector<float> depthOf(float value) {
    return std::vector<float>(size_t(kWidth) * kHeight, value);
}

// Every channel 0 left of column `edge`, 1 from it on.
std::vector<float> stepEdge(uint32_t edge) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x)
            for (int c = 0; c < 4; ++c) rgba[(size_t(y) * kWidth + x) * 4 + c] = x >= edge ? 1.0f : 0.0f;
    return rgba;
}

// Standard deviation of the line spread function (the derivative of a step's response) along row `y`, channel c.
double lineSpreadSigma(const std::vector<float>& rgba, uint32_t y, int c) {
    double sum = 0.0, first = 0.0, second = 0.0;
    for (uint32_t x = 0; x + 1 < kWidth; ++x) {
        const double d = double(rgba[(size_t(y) * kWidth + x + 1) * 4 + c]) - rgba[(size_t(y) * kWidth + x) * 4 + c];
        sum += d;
        first += d * x;
        second += d * double(x) * x;
    }
    const double mean = first / sum;
    return std::sqrt(second / sum - mean * mean);
}

bool bitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::string parseError(const nlohmann::json& j) {
    return test::errorOf([&] { parseSensor(j, "scene.json", "camera.sensor"); });
}

} // namespace

TEST(SensorOptics, NoOpticsKeysIsBitwiseIdentity) {
    SensorParams p;
    p.enabled = true;
    p.optics.pixelSizeUm = 7.0;    // no effect without an aperture
    p.optics.focusDistanceM = 2.0; // no effect either
    p.electronsPerUnit = 0.0;
    const SensorOptics optics(p, testCamera());
    EXPECT_FALSE(optics.active());
    std::vector<float> image = texture(), original = image;
    image[7] = kInf;
    original[7] = kInf;
    optics.apply(depthOf(1.0f), image);
    EXPECT_TRUE(bitwiseEqual(image, original));
    std::vector<uint16_t> half(image.size());
    for (size_t i = 0; i < half.size(); ++i) half[i] = uint16_t(i * 7919u);
    const std::vector<uint16_t> halfOriginal = half;
    optics.applyHalf(depthOf(1.0f), half);
    EXPECT_EQ(half, halfOriginal);

    SensorParams disabled = wideOpen(); // a disabled sensor ignores its lens too
    disabled.enabled = false;
    EXPECT_FALSE(SensorOptics(disabled, testCamera()).active());
}

// The acceptance's "a textured plane at the focus distance stays sharp": every pixel, bit for bit.
TEST(SensorOptics, PlaneAtTheFocusDistanceKeepsEveryPixel) {
    const SensorOptics optics(wideOpen(), testCamera(kLongFx));
    std::vector<float> image = texture();
    const std::vector<float> original = image;
    optics.apply(depthOf(kFocus), image);
    EXPECT_TRUE(bitwiseEqual(image, original));
}

// Left half at the focus distance, right half far behind it: the sharp half takes no light from the blurred one, so
// its edge stays bit for bit; the background is blurred up to the edge. A blurred foreground in front of a sharp
// background does spread over it.
TEST(SensorOptics, InFocusEdgeDoesNotTakeLightFromTheBlurredBackground) {
    const SensorOptics optics(wideOpen(), testCamera(kLongFx));
    std::vector<float> depth(size_t(kWidth) * kHeight);
    for (size_t p = 0; p < depth.size(); ++p) depth[p] = p % kWidth < kWidth / 2 ? kFocus : 4.0f * kFocus;
    std::vector<float> image = texture();
    const std::vector<float> original = image;
    optics.apply(depth, image);
    size_t sharpChanged = 0, blurredChanged = 0;
    for (size_t i = 0; i < image.size(); ++i) {
        const bool sharp = (i / 4) % kWidth < kWidth / 2;
        (sharp ? sharpChanged : blurredChanged) += image[i] != original[i];
    }
    EXPECT_EQ(sharpChanged, 0u);
    EXPECT_GT(blurredChanged, image.size() / 2 * 9 / 10);

    for (size_t p = 0; p < depth.size(); ++p) depth[p] = p % kWidth < kWidth / 2 ? 0.5f * kFocus : kFocus; // near blur
    image = original;
    optics.apply(depth, image);
    const size_t besideEdge = (size_t(kHeight / 2) * kWidth + kWidth / 2 + 2) * 4; // sharp, 3 px from the edge
    EXPECT_NE(image[besideEdge], original[besideEdge]);
    const size_t farFromEdge = (size_t(kHeight / 2) * kWidth + kWidth - 20) * 4;
    EXPECT_EQ(image[farFromEdge], original[farFromEdge]);
}

// The acceptance's "one at twice the distance is blurred by the thin-lens circle of confusion within 10 %": a step
// edge's line spread is the disc's projection, whose standard deviation is the radius / 2.
TEST(SensorOptics, PlaneAtTwiceTheFocusDistanceIsBlurredByTheThinLensCircle) {
    const SensorParams p = wideOpen();
    const SensorOptics optics(p, testCamera(kLongFx));
    const double predicted = predictedCocPx(p, kLongFx, 2.0 * kFocus);
    EXPECT_NEAR(2.0 * optics.cocRadiusPx(2.0 * kFocus), predicted, 1e-9 * predicted);
    ASSERT_GT(predicted, 8.0);
    ASSERT_LT(predicted / 2.0, kMaxCocRadiusPx);
    std::vector<float> image = stepEdge(kWidth / 2);
    optics.apply(depthOf(2.0f * kFocus), image);
    const double measured = 4.0 * lineSpreadSigma(image, kHeight / 2, 1); // diameter = 2 radius = 4 sigma
    EXPECT_NEAR(measured / predicted, 1.0, 0.10) << "measured " << measured << " px, predicted " << predicted;
}

TEST(SensorOptics, SkyIsDefocusedAsInfinitelyFar) {
    const SensorParams p = wideOpen();
    const SensorOptics optics(p, testCamera(kLongFx));
    const double pitch = 5e-6, f = kLongFx * pitch, a = f / 1.0;
    EXPECT_DOUBLE_EQ(optics.cocRadiusPx(INFINITY), 0.5 * a * f / (double(kFocus) - f) / pitch);
    EXPECT_DOUBLE_EQ(optics.cocRadiusPx(NAN), optics.cocRadiusPx(INFINITY));
    EXPECT_NEAR(optics.cocRadiusPx(1e9), optics.cocRadiusPx(INFINITY), 1e-6);
    EXPECT_EQ(optics.cocRadiusPx(kFocus), 0.0);
    EXPECT_LT(optics.cocRadiusPx(INFINITY), kMaxCocRadiusPx); // the tests' discs are not capped
}

// The MTF's Gaussian measured back from an edge's line spread, at a sub-pixel and a wider sigma.
TEST(SensorOptics, MtfSigmaMeasuredFromAnEdge) {
    for (double sigma : {0.4, 1.3, 3.0}) {
        SensorParams p;
        p.enabled = true;
        p.optics.mtfSigmaPx = sigma;
        const SensorOptics optics(p, testCamera());
        double total = optics.mtfKernel()[0];
        for (size_t k = 1; k < optics.mtfKernel().size(); ++k) total += 2.0 * optics.mtfKernel()[k];
        EXPECT_NEAR(total, 1.0, 1e-6);
        std::vector<float> image = stepEdge(kWidth / 2);
        optics.apply({}, image); // no aperture: no depth needed
        EXPECT_NEAR(lineSpreadSigma(image, kHeight / 2, 0) / sigma, 1.0, 0.05) << "sigma " << sigma;
        EXPECT_NEAR(lineSpreadSigma(image, 3, 3) / sigma, 1.0, 0.05) << "alpha blurs with the colour";
    }
}

// A small bright blob near the lower right corner: red moves out along the radius by the aberration times the
// blob's share of the corner radius, blue as far in, green stays.
TEST(SensorOptics, ChromaticAberrationShiftsRedOutAndBlueInAtTheCorner) {
    SensorParams p;
    p.enabled = true;
    p.optics.chromaticAberrationPx = 2.0;
    const Intrinsics camera = testCamera();
    const SensorOptics optics(p, camera);
    const double bx = 140.0, by = 105.0; // blob centre, pixel coordinates (centres at i + 0.5)
    std::vector<float> image(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const double dx = x + 0.5 - bx, dy = y + 0.5 - by;
            const float v = float(std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5)));
            for (int c = 0; c < 4; ++c) image[(size_t(y) * kWidth + x) * 4 + c] = c == 3 ? 1.0f : v;
        }
    optics.apply({}, image);
    auto centroid = [&](int c) {
        double sum = 0.0, sx = 0.0, sy = 0.0;
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                const double v = image[(size_t(y) * kWidth + x) * 4 + c];
                sum += v;
                sx += v * (x + 0.5);
                sy += v * (y + 0.5);
            }
        return std::pair{sx / sum, sy / sum};
    };
    const double corner = std::sqrt(80.0 * 80.0 + 60.0 * 60.0), scale = 2.0 / corner;
    const double ex = (bx - camera.cx) * scale, ey = (by - camera.cy) * scale; // expected red shift
    auto [rx, ry] = centroid(0);
    auto [gx, gy] = centroid(1);
    auto [ux, uy] = centroid(2);
    EXPECT_NEAR(gx, bx, 0.01);
    EXPECT_NEAR(gy, by, 0.01);
    EXPECT_NEAR(rx - gx, ex, 0.05);
    EXPECT_NEAR(ry - gy, ey, 0.05);
    EXPECT_NEAR(ux - gx, -ex, 0.05);
    EXPECT_NEAR(uy - gy, -ey, 0.05);
    EXPECT_GT(ex, 1.1); // a shift worth measuring: 1.2 of the 2 px the corner gets
}

// Depth of field, MTF and chromatic aberration together on a scene of many depths and a sky: the same bits for any
// thread count; the half variant is the float one rounded.
TEST(SensorOptics, ResultsDoNotDependOnTheThreadCount) {
    SensorParams p = wideOpen();
    p.optics.mtfSigmaPx = 0.7;
    p.optics.chromaticAberrationPx = -1.5;
    std::vector<float> depth(size_t(kWidth) * kHeight);
    for (size_t i = 0; i < depth.size(); ++i)
        depth[i] = i % 13 == 0 ? kInf : 0.2f + float((i * 40503u) % 977u) / 400.0f;
    std::vector<float> one = texture(), three = texture();
    SensorOptics(p, testCamera(kLongFx), 1).apply(depth, one);
    SensorOptics(p, testCamera(kLongFx), 3).apply(depth, three);
    EXPECT_TRUE(bitwiseEqual(one, three));
    EXPECT_FALSE(bitwiseEqual(one, texture()));

    std::vector<uint16_t> half(one.size());
    std::vector<float> fromHalf(one.size());
    const std::vector<float> source = texture();
    for (size_t i = 0; i < half.size(); ++i) {
        half[i] = floatToHalfBits(source[i]);
        fromHalf[i] = halfBitsToFloat(half[i]);
    }
    SensorOptics(p, testCamera(kLongFx), 2).applyHalf(depth, half);
    SensorOptics(p, testCamera(kLongFx), 1).apply(depth, fromHalf);
    for (size_t i = 0; i < half.size(); ++i) ASSERT_EQ(half[i], floatToHalfBits(fromHalf[i])) << i;
}

// Each view is defocused by the depth it is given: the right view's own depth, not the left's.
TEST(SensorOptics, EachViewIsDefocusedByItsOwnDepth) {
    const SensorOptics optics(wideOpen(), testCamera(kLongFx));
    std::vector<float> leftDepth = depthOf(kFocus), rightDepth = depthOf(kFocus);
    for (size_t p = 0; p < rightDepth.size(); ++p)
        if (p % kWidth >= 100) rightDepth[p] = 4.0f * kFocus; // the right view sees a background the left one does not
    std::vector<float> left = texture(), right = texture();
    optics.apply(leftDepth, left);
    optics.apply(rightDepth, right);
    EXPECT_TRUE(bitwiseEqual(left, texture()));
    EXPECT_FALSE(bitwiseEqual(right, texture()));
}

TEST(SensorOptics, ParsesTheLensKeysAndRecordsThemOnlyWhenActive) {
    const nlohmann::json j = {{"mtf_sigma_px", 0.6},
                              {"aperture_f", 2.8},
                              {"focus_distance_m", 3.0},
                              {"pixel_size_um", 2.2},
                              {"chromatic_aberration_px", -0.5}};
    const SensorParams p = parseSensor(j, "s.json", "camera.sensor");
    EXPECT_EQ(p.optics.mtfSigmaPx, 0.6);
    EXPECT_EQ(p.optics.apertureF, 2.8);
    EXPECT_EQ(p.optics.focusDistanceM, 3.0);
    EXPECT_EQ(p.optics.pixelSizeUm, 2.2);
    EXPECT_EQ(p.optics.chromaticAberrationPx, -0.5);
    const nlohmann::json written = sensorToJson(p);
    for (const auto& [key, value] : j.items()) EXPECT_EQ(written.at(key), value) << key;
    EXPECT_EQ(sensorToJson(parseSensor(written, "s.json", "x")), written);
    // A sensor without optics records exactly what it recorded before the lens existed.
    const nlohmann::json plain = sensorToJson(parseSensor({{"k1", 0.01}}, "s.json", "x"));
    for (const char* key :
         {"mtf_sigma_px", "aperture_f", "focus_distance_m", "pixel_size_um", "chromatic_aberration_px"})
        EXPECT_FALSE(plain.contains(key)) << key;
    EXPECT_EQ(parseSensor({{"mtf_sigma_px", 1}}, "s.json", "x").optics.pixelSizeUm, 3.45); // the default pitch
}

TEST(SensorOptics, BadLensKeysNameTheKey) {
    EXPECT_EQ(parseError({{"mtf_sigma_px", -0.1}}),
              "scene.json: 'camera.sensor.mtf_sigma_px' must be between 0 and 5 (got -0.1)");
    EXPECT_EQ(parseError({{"mtf_sigma_px", 6}}),
              "scene.json: 'camera.sensor.mtf_sigma_px' must be between 0 and 5 (got 6)");
    EXPECT_EQ(parseError({{"mtf_sigma_px", "soft"}}), "scene.json: 'camera.sensor.mtf_sigma_px' must be a number");
    EXPECT_EQ(parseError({{"aperture_f", 0.5}, {"focus_distance_m", 2}}),
              "scene.json: 'camera.sensor.aperture_f' must be 0 (a pinhole) or between 0.7 and 64 (got 0.5)");
    EXPECT_EQ(parseError({{"aperture_f", 65}, {"focus_distance_m", 2}}),
              "scene.json: 'camera.sensor.aperture_f' must be between 0 and 64 (got 65)");
    EXPECT_EQ(parseError({{"aperture_f", 2}}),
              "scene.json: 'camera.sensor.focus_distance_m' is required when 'aperture_f' is greater than 0");
    EXPECT_EQ(parseError({{"aperture_f", 2}, {"focus_distance_m", 0}}),
              "scene.json: 'camera.sensor.focus_distance_m' must be greater than 0");
    EXPECT_EQ(parseError({{"aperture_f", 2}, {"focus_distance_m", -1}}),
              "scene.json: 'camera.sensor.focus_distance_m' must be between 0 and 1e+06 (got -1)");
    EXPECT_EQ(parseError({{"pixel_size_um", 0.1}}),
              "scene.json: 'camera.sensor.pixel_size_um' must be between 0.5 and 100 (got 0.1)");
    EXPECT_EQ(parseError({{"pixel_size_um", 200}}),
              "scene.json: 'camera.sensor.pixel_size_um' must be between 0.5 and 100 (got 200)");
    EXPECT_EQ(parseError({{"chromatic_aberration_px", 11}}),
              "scene.json: 'camera.sensor.chromatic_aberration_px' must be between -10 and 10 (got 11)");
    EXPECT_EQ(parseError({{"chromatic_aberration_px", true}}),
              "scene.json: 'camera.sensor.chromatic_aberration_px' must be a number");
    // Focused inside the focal length (fx 100 px * 3.45 um = 0.345 mm): refused once the camera is known.
    const SensorParams p = parseSensor({{"aperture_f", 2}, {"focus_distance_m", 0.0003}}, "s.json", "x");
    try {
        SensorModel model(p, testCamera());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "'focus_distance_m' (0.0003 m) must exceed the focal length fx * 'pixel_size_um' (0.000345 m)");
    }
    EXPECT_THROW(SensorOptics(p, testCamera()), Error);
}
