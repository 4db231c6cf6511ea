// End-point error and KITTI Fl on hand-made flow fields whose every figure is known exactly.
#include "eval/flow_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sward;

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

} // namespace

TEST(FlowMetrics, EndPointErrorIsTheEuclideanLengthOfTheDifference) {
    FlowAccumulator a;
    a.add(4.0f, 6.0f, 1.0f, 2.0f);  // (3, 4): 5 px
    a.add(1.0f, 1.0f, 1.0f, 1.0f);  // exact
    a.add(-1.0f, 0.0f, 0.0f, 0.0f); // 1 px
    const FlowMetrics m = a.metrics();
    EXPECT_EQ(m.gtPixels, 3u);
    EXPECT_EQ(m.estimatedPixels, 3u);
    EXPECT_DOUBLE_EQ(m.epe, 2.0);
    EXPECT_DOUBLE_EQ(m.rmsEpe, std::sqrt(26.0 / 3));
    EXPECT_DOUBLE_EQ(m.maxEpe, 5.0);
    EXPECT_DOUBLE_EQ(m.bad[0], 1.0 / 3); // EPE > 1: only the 5 px pixel (1 px is not more than 1)
    EXPECT_DOUBLE_EQ(m.bad[1], 1.0 / 3);
    EXPECT_DOUBLE_EQ(m.meanTruthMagnitude, (std::sqrt(5.0) + std::sqrt(2.0)) / 3);
}

TEST(FlowMetrics, FlNeedsMoreThanThreePixelsAndMoreThanFivePercentOfTheTruth) {
    FlowAccumulator a;
    a.add(104.0f, 0.0f, 100.0f, 0.0f); // 4 px > 3 but < 5 % of 100: not an outlier
    a.add(106.0f, 0.0f, 100.0f, 0.0f); // 6 px > 5 % of 100: outlier
    a.add(13.5f, 0.0f, 10.0f, 0.0f);   // 3.5 px > 3 and > 0.5: outlier
    a.add(12.9f, 0.0f, 10.0f, 0.0f);   // 2.9 px: not
    a.add(0.0f, 3.0f, 0.0f, 0.0f);     // exactly 3 px: not (strictly more than 3)
    EXPECT_DOUBLE_EQ(a.metrics().fl, 2.0 / 5);
    EXPECT_FALSE(isFlOutlier(3.0, 0.0));
    EXPECT_TRUE(isFlOutlier(3.01, 60.0));
    EXPECT_FALSE(isFlOutlier(3.01, 61.0));
}

TEST(FlowMetrics, InvalidEstimatesOnlyLowerCoverage) {
    FlowAccumulator a;
    a.add(kNan, kNan, 1.0f, 1.0f);
    a.add(2.0f, 1.0f, 1.0f, 1.0f);
    const FlowMetrics m = a.metrics();
    EXPECT_EQ(m.gtPixels, 2u);
    EXPECT_EQ(m.estimatedPixels, 1u);
    EXPECT_DOUBLE_EQ(m.coverage, 0.5);
    EXPECT_DOUBLE_EQ(m.epe, 1.0);
    FlowAccumulator empty;
    empty.add(kNan, kNan, 0.0f, 0.0f);
    EXPECT_TRUE(std::isnan(empty.metrics().epe));
    EXPECT_TRUE(std::isnan(empty.metrics().fl));
    EXPECT_DOUBLE_EQ(empty.metrics().coverage, 0.0);
}

TEST(FlowMetrics, NocCountsOnlyVisiblePixelsAndAllCountsEvery) {
    FlowErrors e;
    e.add(3.0f, 4.0f, 0.0f, 0.0f, false); // occluded, 5 px off
    e.add(1.0f, 0.0f, 1.0f, 0.0f, true);  // visible, exact
    EXPECT_DOUBLE_EQ(e.all.metrics().epe, 2.5);
    EXPECT_DOUBLE_EQ(e.noc.metrics().epe, 0.0);
    EXPECT_EQ(e.noc.metrics().gtPixels, 1u);
    EXPECT_DOUBLE_EQ(e.all.metrics().fl, 0.5);
    EXPECT_DOUBLE_EQ(e.noc.metrics().fl, 0.0);
}

TEST(FlowMetrics, MergingEqualsAccumulatingEverythingInOne) {
    FlowAccumulator one, first, second;
    const float values[][4] = {{1, 2, 0, 0}, {5, 5, 1, 1}, {0.5f, 0, 0, 0}, {9, 0, 1, 0}};
    for (int i = 0; i < 4; ++i) {
        one.add(values[i][0], values[i][1], values[i][2], values[i][3]);
        (i < 2 ? first : second).add(values[i][0], values[i][1], values[i][2], values[i][3]);
    }
    first.merge(second);
    const FlowMetrics a = one.metrics(), b = first.metrics();
    EXPECT_EQ(a.epe, b.epe);
    EXPECT_EQ(a.fl, b.fl);
    EXPECT_EQ(a.maxEpe, b.maxEpe);
    EXPECT_EQ(a.gtPixels, b.gtPixels);
}

TEST(FlowMetrics, ComputeFlowMetricsSkipsPixelsWithoutTruthAndRefusesOtherSizes) {
    const FlowField truth{2, 1, {kNan, kNan, 1.0f, 1.0f}};
    const FlowField estimate{2, 1, {50.0f, 50.0f, 1.0f, 2.0f}};
    const FlowMetrics m = computeFlowMetrics(estimate, truth);
    EXPECT_EQ(m.gtPixels, 1u);
    EXPECT_DOUBLE_EQ(m.epe, 1.0);
    EXPECT_THROW(computeFlowMetrics(FlowField{1, 1, {0, 0}}, truth), std::exception);
}
