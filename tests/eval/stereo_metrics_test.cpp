// Stereo metrics on synthetic maps of known error: every figure below is worked out by hand.
#include "eval/stereo_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace sward;

TEST(StereoMetrics, ConstantPlusOnePixelEstimate) {
    std::vector<float> truth(200), estimate(200);
    for (size_t i = 0; i < truth.size(); ++i) {
        truth[i] = 5.0f + float(i) * 0.25f;
        estimate[i] = truth[i] + 1.0f;
    }
    StereoMetrics m = computeMetrics(estimate, truth);
    EXPECT_EQ(m.gtPixels, 200u);
    EXPECT_EQ(m.estimatedPixels, 200u);
    EXPECT_DOUBLE_EQ(m.coverage, 1.0);
    EXPECT_DOUBLE_EQ(m.meanError, 1.0);
    EXPECT_DOUBLE_EQ(m.meanAbsError, 1.0);
    EXPECT_NEAR(m.stdError, 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(m.rms, 1.0);
    EXPECT_DOUBLE_EQ(m.bad[0], 1.0); // bad-0.5 = 100 %
    EXPECT_DOUBLE_EQ(m.bad[1], 0.0); // bad-1 = 0 %: |e| must exceed the threshold
    EXPECT_DOUBLE_EQ(m.bad[2], 0.0);
    EXPECT_DOUBLE_EQ(m.bad[3], 0.0);
    for (double a : m.accuracy) EXPECT_DOUBLE_EQ(a, 1.0);
    EXPECT_DOUBLE_EQ(m.d1, 0.0);
    EXPECT_NEAR(m.stdError8bit, 0.0, 1e-9);
}

TEST(StereoMetrics, SignedStatisticsOfKnownErrors) {
    // Errors -2, +2, +4, 0: mean 1, mean |e| 2, variance (9 + 1 + 9 + 1) / 4 = 5, RMS sqrt(24 / 4).
    std::vector<float> truth = {10, 20, 30, 40}, estimate = {8, 22, 34, 40};
    StereoMetrics m = computeMetrics(estimate, truth);
    EXPECT_DOUBLE_EQ(m.meanError, 1.0);
    EXPECT_DOUBLE_EQ(m.meanAbsError, 2.0);
    EXPECT_NEAR(m.stdError, std::sqrt(5.0), 1e-12);
    EXPECT_NEAR(m.rms, std::sqrt(6.0), 1e-12);
    EXPECT_DOUBLE_EQ(m.maxAbsError, 4.0);
    EXPECT_DOUBLE_EQ(m.bad[0], 0.75);
    EXPECT_DOUBLE_EQ(m.bad[2], 0.25);     // only |e| = 4 exceeds 2
    EXPECT_DOUBLE_EQ(m.bad[3], 0.0);      // and it does not exceed 4
    EXPECT_DOUBLE_EQ(m.accuracy[0], 2.0); // 2 of 4 pixels have |e| <= 2
    EXPECT_DOUBLE_EQ(m.accuracy[3], 4.0);
}

TEST(StereoMetrics, D1AppliesBothThreeAndFivePercentRules) {
    struct Case {
        float truth, estimate;
        bool outlier;
    };
    const Case cases[] = {
        {100.0f, 104.9f, false}, // 4.9 px > 3 px but < 5 px = 5 % of 100
        {100.0f, 105.1f, true},  // 5.1 px > both
        {50.0f, 53.1f, true},    // 3.1 px > 3 px and > 2.5 px
        {50.0f, 46.9f, true},    // the sign does not matter
        {20.0f, 22.9f, false},   // 2.9 px > 1 px (5 %) but not > 3 px
        {200.0f, 209.0f, false}, // 9 px < 10 px
    };
    std::vector<float> truth, estimate;
    int outliers = 0;
    for (const Case& c : cases) {
        truth.push_back(c.truth);
        estimate.push_back(c.estimate);
        outliers += c.outlier;
        EXPECT_EQ(isD1Outlier(std::abs(double(c.estimate) - double(c.truth)), c.truth), c.outlier)
            << "gt " << c.truth << " est " << c.estimate;
        StereoMetrics one = computeMetrics(std::vector<float>{c.estimate}, std::vector<float>{c.truth});
        EXPECT_DOUBLE_EQ(one.d1, c.outlier ? 1.0 : 0.0) << "gt " << c.truth << " est " << c.estimate;
    }
    EXPECT_DOUBLE_EQ(computeMetrics(estimate, truth).d1, double(outliers) / double(std::size(cases)));
}

TEST(StereoMetrics, InvalidEstimatesAreExcludedFromErrorsAndLowerCoverage) {
    // Four valid estimates with error +1 and four invalid ones in every encoding a matcher may use.
    std::vector<float> truth = {10, 10, 10, 10, 10, 10, 10, 10};
    std::vector<float> estimate = {11, 11, 11, 11, 0.0f, -1.0f, INFINITY, NAN};
    StereoMetrics m = computeMetrics(estimate, truth);
    EXPECT_EQ(m.gtPixels, 8u);
    EXPECT_EQ(m.estimatedPixels, 4u);
    EXPECT_DOUBLE_EQ(m.coverage, 0.5);
    EXPECT_DOUBLE_EQ(m.meanError, 1.0);
    EXPECT_DOUBLE_EQ(m.maxAbsError, 1.0);
    EXPECT_DOUBLE_EQ(m.bad[1], 0.0);
}

TEST(StereoMetrics, PixelsWithoutGroundTruthAreIgnored) {
    std::vector<float> truth = {0.0f, INFINITY, NAN, 10.0f}, estimate = {50, 50, 50, 12};
    StereoMetrics m = computeMetrics(estimate, truth);
    EXPECT_EQ(m.gtPixels, 1u);
    EXPECT_DOUBLE_EQ(m.meanError, 2.0);
}

TEST(StereoMetrics, NoEstimatesGiveNaNErrorsAndZeroCoverage) {
    std::vector<float> truth = {10, 20}, estimate = {0, 0};
    StereoMetrics m = computeMetrics(estimate, truth);
    EXPECT_DOUBLE_EQ(m.coverage, 0.0);
    EXPECT_TRUE(std::isnan(m.meanAbsError));
    EXPECT_TRUE(std::isnan(m.d1));
}

TEST(StereoMetrics, MergedAccumulatorsEqualOnePass) {
    std::vector<float> truth, estimate;
    for (int i = 0; i < 1000; ++i) {
        truth.push_back(1.0f + float(i % 97));
        estimate.push_back(i % 13 == 0 ? 0.0f : truth.back() + float((i * 37) % 23 - 11) * 0.37f);
    }
    ErrorAccumulator whole, a, b;
    whole.addMaps(estimate, truth);
    a.addMaps(std::span(estimate).first(400), std::span(truth).first(400));
    b.addMaps(std::span(estimate).subspan(400), std::span(truth).subspan(400));
    a.merge(b);
    StereoMetrics x = whole.metrics(), y = a.metrics();
    EXPECT_EQ(x.estimatedPixels, y.estimatedPixels);
    EXPECT_NEAR(x.meanError, y.meanError, 1e-12);
    EXPECT_NEAR(x.stdError, y.stdError, 1e-12);
    EXPECT_EQ(x.bad, y.bad);
    EXPECT_EQ(x.accuracy, y.accuracy);
    EXPECT_EQ(x.d1, y.d1);
    EXPECT_EQ(whole.signedHistogram(), a.signedHistogram());
}

TEST(StereoMetrics, AccuracyQuantilesResolveTo1Over256Pixel) {
    // |e| = 0.1, 0.2, ..., 10.0: A50 = 5.0, A90 = 9.0, A99 = 9.9, each rounded down to 1/256 px.
    std::vector<float> truth(100, 50.0f), estimate(100);
    for (int i = 0; i < 100; ++i) estimate[i] = 50.0f + 0.1f * float(i + 1);
    StereoMetrics m = computeMetrics(estimate, truth);
    const double expected[] = {5.0, 9.0, 9.5, 9.9};
    for (size_t q = 0; q < 4; ++q) {
        EXPECT_LE(m.accuracy[q], expected[q] + 1e-5) << q;
        EXPECT_GT(m.accuracy[q], expected[q] - 1.0 / 256.0 - 1e-5) << q;
    }
}

TEST(StereoMetrics, SignedDifferenceImageIsShiftedTo127AndClamped) {
    EXPECT_EQ(signedDifference8(0.0), 127);
    EXPECT_EQ(signedDifference8(1.4), 128);
    EXPECT_EQ(signedDifference8(-1.6), 125);
    EXPECT_EQ(signedDifference8(128.0), 255);
    EXPECT_EQ(signedDifference8(500.0), 255);
    EXPECT_EQ(signedDifference8(-127.0), 0);
    EXPECT_EQ(signedDifference8(-300.0), 0);
}
