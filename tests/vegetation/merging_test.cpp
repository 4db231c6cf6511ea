// Far billboards narrower than a few pixels merge into fewer, wider ones (gpu::mergeWidthScale).
#include "shared/gpu_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

using namespace sward;

namespace {

constexpr int kSteps = 200000;

// Expected drawn width per plant over the plant hash u, in units of its own width.
double expectedWidth(float mergeWidth, float widthPixels) {
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i)
        sum += gpu::mergeWidthScale(mergeWidth, widthPixels, (float(i) + 0.5f) / float(kSteps));
    return sum / kSteps;
}

double keptShare(float mergeWidth, float widthPixels) {
    int kept = 0;
    for (int i = 0; i < kSteps; ++i)
        kept += gpu::mergeWidthScale(mergeWidth, widthPixels, (float(i) + 0.5f) / float(kSteps)) > 0.0f;
    return double(kept) / kSteps;
}

} // namespace

TEST(Merging, KeepsTheExpectedWidthSoCoverageIsUnchanged) {
    // From a billboard as wide as the merge width down to the widening limit, and in the continuous zone between.
    for (float pixels : {6.0f, 5.0f, 3.0f, 1.5f, 1.0f, 0.5f})
        EXPECT_NEAR(expectedWidth(6.0f, pixels), 1.0, 1e-3) << pixels << " px";
    EXPECT_NEAR(keptShare(6.0f, 1.5f), 0.25 / (1.0 - 0.5 * gpu::kMergeFade), 1e-3)
        << "a quarter, plus the shrinking zone";
}

TEST(Merging, WideBillboardsAndOffAreExactlyUntouched) {
    for (float u : {0.0f, 0.5f, 0.99999f}) {
        EXPECT_EQ(gpu::mergeWidthScale(6.0f, 7.0f, u), 1.0f);
        EXPECT_EQ(gpu::mergeWidthScale(0.0f, 0.2f, u), 1.0f) << "off";
    }
    EXPECT_EQ(1.0f * gpu::kWidthScaleUnit, 32.0f) << "a scale of 1 is stored exactly";
}

TEST(Merging, WidensAtMostToTheLimitAndNarrowBillboardsBecomeAsWideAsTheMergeWidth) {
    float widest = 0.0f;
    for (int i = 0; i < kSteps; ++i) widest = std::max(widest, gpu::mergeWidthScale(6.0f, 0.1f, float(i) / kSteps));
    EXPECT_NEAR(widest, gpu::kMaxMergeWiden, 1e-3) << "0.1 px wide: widened 6x, not 60x";
    EXPECT_NEAR(gpu::mergeWidthScale(6.0f, 2.0f, 0.0f) * 2.0f, 6.0f, 1e-4)
        << "a kept 2 px billboard is drawn 6 px wide";
}

TEST(Merging, APlantsWidthChangesContinuouslyWithItsDistance) {
    // As the camera moves away a billboard narrows on screen: its scale grows, then shrinks to nothing, never pops.
    for (float u : {0.1f, 0.35f, 0.6f, 0.9f}) {
        float previous = gpu::mergeWidthScale(6.0f, 8.0f, u) * 8.0f; // drawn width in pixels
        for (float pixels = 8.0f; pixels > 0.3f; pixels -= 0.001f) {
            float drawn = gpu::mergeWidthScale(6.0f, pixels, u) * pixels;
            ASSERT_LE(std::abs(drawn - previous), 0.05f) << "u " << u << " at " << pixels << " px";
            previous = drawn;
        }
    }
}

TEST(Merging, PlantHashesAreUniformAndFixed) {
    // A biased hash would merge some plants (categories, rows of the field) more than others.
    int quarter[4] = {0, 0, 0, 0};
    for (uint32_t i = 0; i < 100000; ++i) ++quarter[int(gpu::mergeHash(i) * 4.0f)];
    for (int q = 0; q < 4; ++q) EXPECT_NEAR(quarter[q], 25000, 600) << "quarter " << q;
    static_assert(gpu::mergeHash(0u) >= 0.0f && gpu::mergeHash(0u) < 1.0f);
    EXPECT_EQ(gpu::mergeHash(12345u), gpu::mergeHash(12345u));
    EXPECT_FLOAT_EQ(gpu::mergeHash(0u), 0.44527441f); // fixed: every merged dataset depends on these values
}

// Merging in depth (gpu::depthMergeScale): the same rule on the billboard's height, bounded by how much cards overlap.
TEST(DepthMerging, OnlyAsFarAsCardsOverlapAtTheViewAngle) {
    auto sinOf = [](double degrees) { return float(std::sin(degrees * 3.14159265358979 / 180.0)); };
    auto deepest = [](float sinView) {
        float most = 0.0f;
        for (int i = 0; i < kSteps; ++i)
            most = std::max(most, gpu::depthMergeScale(16.0f, 0.5f, sinView, float(i) / kSteps));
        return most;
    };
    // Seen more steeply than atan(1 / kDepthMergeGrazing), 3.6 degrees: nothing merges, exactly (mergeScale's fade
    // zone would still thin plants at the threshold: the threshold itself fades out).
    for (float u : {0.0f, 0.5f, 0.99999f}) {
        EXPECT_EQ(gpu::depthMergeScale(16.0f, 0.5f, sinOf(10.0), u), 1.0f) << "10 degrees";
        EXPECT_EQ(gpu::depthMergeScale(16.0f, 0.5f, sinOf(90.0), u), 1.0f) << "from above";
        EXPECT_EQ(gpu::depthMergeScale(0.0f, 0.5f, sinOf(0.5), u), 1.0f) << "off";
        EXPECT_EQ(gpu::depthMergeScale(16.0f, 20.0f, sinOf(0.5), u), 1.0f) << "taller than the threshold";
    }
    // 1.8 degrees: cot 31.8, so one card stands for at most 31.8 / 16 plants; 0.5 degrees: the limit of 6.
    EXPECT_NEAR(deepest(sinOf(1.8)), 1.0 / (std::tan(1.8 * 3.14159265358979 / 180.0) * gpu::kDepthMergeGrazing), 2e-3);
    EXPECT_NEAR(deepest(sinOf(0.5)), gpu::kMaxDepthMerge, 1e-3);
    // The expected scale per plant is 1 (mergeScale's rule), and it changes continuously with the height on screen.
    for (float pixels : {16.0f, 8.0f, 3.0f, 1.0f}) {
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i)
            sum += gpu::depthMergeScale(16.0f, pixels, sinOf(0.5), (float(i) + 0.5f) / kSteps);
        EXPECT_NEAR(sum / kSteps, 1.0, 1e-3) << pixels << " px";
    }
    for (float u : {0.1f, 0.4f, 0.8f}) {
        float previous = gpu::depthMergeScale(16.0f, 20.0f, sinOf(0.5), u);
        for (float pixels = 20.0f; pixels > 0.5f; pixels -= 0.001f) {
            const float scale = gpu::depthMergeScale(16.0f, pixels, sinOf(0.5), u);
            ASSERT_LE(std::abs(scale - previous), 0.05f) << "u " << u << " at " << pixels << " px";
            previous = scale;
        }
    }
}

// Each per-plant decision has its own hash (gpu::plantHash): one keyed like another would pick the same plants (the
// depth merge once shared its key with the shadow cascade's blend band). Every pair is checked on the decision's own
// terms: the plants below a quarter under both hashes are a sixteenth of all, and the values are uncorrelated.
TEST(PlantHashes, AreUncorrelated) {
    using Hash = float (*)(uint32_t);
    const std::pair<const char*, Hash> hashes[] = {{"width merge", [](uint32_t i) { return gpu::mergeHash(i); }},
                                                   {"depth merge", [](uint32_t i) { return gpu::depthMergeHash(i); }},
                                                   {"shadow", [](uint32_t i) { return gpu::plantShadowHash(i); }},
                                                   {"colour", [](uint32_t i) { return gpu::plantColourHash(i); }}};
    constexpr uint32_t kPlants = 1u << 18;
    for (size_t a = 0; a < std::size(hashes); ++a)
        for (size_t b = a + 1; b < std::size(hashes); ++b) {
            double sa = 0.0, sb = 0.0, sab = 0.0, saa = 0.0, sbb = 0.0;
            uint32_t both = 0;
            for (uint32_t i = 0; i < kPlants; ++i) {
                const double u = hashes[a].second(i), v = hashes[b].second(i);
                sa += u, sb += v, sab += u * v, saa += u * u, sbb += v * v;
                both += u < 0.25 && v < 0.25;
            }
            const double n = kPlants, cov = sab / n - sa / n * (sb / n);
            const double r = cov / std::sqrt((saa / n - sa / n * (sa / n)) * (sbb / n - sb / n * (sb / n)));
            const std::string pair = std::string(hashes[a].first) + " / " + hashes[b].first;
            EXPECT_LT(std::abs(r), 0.01) << pair;
            EXPECT_NEAR(both / n, 1.0 / 16.0, 0.002) << pair; // binomial sd 0.0005
        }
    // Fixed, as mergeHash is (Merging.PlantHashesAreUniformAndFixed): datasets depend on these values.
    EXPECT_FLOAT_EQ(gpu::depthMergeHash(0u), 0.37910241f);
    EXPECT_FLOAT_EQ(gpu::plantShadowHash(0u), 0.81824923f);
}
