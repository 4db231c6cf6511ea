// Far billboards drawn only above the height a grazing ray reaches through a few layers of card (gpu::sliceHeight).
#include "shared/gpu_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace sward;

namespace {

constexpr double kPi = 3.14159265358979;

// Expected layers of card a ray at `degrees` above the ground crosses above height z, exactly: per plant of height h,
// card * h of opaque width per metre of height below its top, divided by the ray's slope.
double layersAbove(const std::vector<float>& heights, float card, float area, double degrees, double z) {
    double sum = 0.0;
    for (float h : heights) sum += card * h * std::max(h - z, 0.0);
    return sum / area / std::tan(degrees * kPi / 180.0);
}

float sliceFor(const std::vector<float>& heights, float card, float area, double degrees, float layers) {
    float cover2 = 0.0f, cover1 = 0.0f;
    for (float h : heights) cover2 += card * h * h / area, cover1 += card * h / area;
    return gpu::sliceHeight(layers, cover2, cover1, float(std::sin(degrees * kPi / 180.0)));
}

} // namespace

TEST(Slicing, TheCutLeavesTheWantedLayersAboveItForEqualPlants) {
    const std::vector<float> heights(500, 0.5f); // 20 plants per m^2 of 25 m^2
    for (double degrees : {1.0, 3.0, 8.0}) {
        const float cut = sliceFor(heights, 0.3f, 25.0f, degrees, 5.0f);
        ASSERT_GT(cut, 0.0f) << degrees;
        EXPECT_NEAR(layersAbove(heights, 0.3f, 25.0f, degrees, cut), 5.0, 1e-3) << degrees << " degrees";
    }
}

TEST(Slicing, WithMixedHeightsTheCutNeverLeavesFewerLayers) {
    // Heights 0.3 .. 0.7 m: the linear form undercounts above the shortest plant, so the cut is low, never high.
    std::vector<float> heights;
    for (int i = 0; i < 500; ++i) heights.push_back(0.3f + 0.4f * float(i) / 499.0f);
    for (double degrees : {0.5, 1.0, 2.0, 4.0}) {
        const float cut = sliceFor(heights, 0.3f, 25.0f, degrees, 5.0f);
        EXPECT_GE(layersAbove(heights, 0.3f, 25.0f, degrees, cut), 5.0 - 1e-3) << degrees << " degrees";
    }
    EXPECT_GT(sliceFor(heights, 0.3f, 25.0f, 0.5, 5.0f), 0.3f) << "at half a degree the short plants are hidden whole";
}

TEST(Slicing, NothingIsCutFromAboveInSparsePlantsOrWhenOff) {
    const std::vector<float> heights(500, 0.5f);
    EXPECT_EQ(sliceFor(heights, 0.3f, 25.0f, 90.0, 5.0f), 0.0f) << "seen from above";
    EXPECT_EQ(sliceFor(heights, 0.3f, 25.0f, 30.0, 5.0f), 0.0f) << "1.04 layers at 30 degrees";
    EXPECT_EQ(sliceFor(heights, 0.3f, 25.0f, 1.0, 0.0f), 0.0f) << "off";
    EXPECT_EQ(gpu::sliceHeight(5.0f, 0.0f, 0.0f, 0.01f), 0.0f) << "an empty cluster";
}

TEST(Slicing, TheCutRisesContinuouslyAsTheViewLowers) {
    const std::vector<float> heights(500, 0.5f);
    float previous = sliceFor(heights, 0.3f, 25.0f, 20.0, 5.0f);
    for (double degrees = 20.0; degrees > 0.2; degrees -= 0.005) {
        const float cut = sliceFor(heights, 0.3f, 25.0f, degrees, 5.0f);
        ASSERT_GE(cut, previous) << degrees;
        ASSERT_LE(cut - previous, 0.01f) << degrees << " degrees: a billboard's bottom edge moves, it does not jump";
        previous = cut;
    }
}
