// Occlusion from both views' ground truth: a pixel is hidden when the other view sees something nearer at its match.
#include "dataset/occlusion.h"

#include <gtest/gtest.h>

using namespace sward;

namespace {

// One row of a scene: background at 2 px; a bar at 6 px over left x = 10..13 (right x = 4..7).
std::vector<float> leftRow() {
    std::vector<float> d(20, 2.0f);
    for (uint32_t x = 10; x < 14; ++x) d[x] = 6.0f;
    return d;
}
std::vector<float> rightRow() {
    std::vector<float> d(20, 2.0f);
    for (uint32_t x = 4; x < 8; ++x) d[x] = 6.0f;
    return d;
}

} // namespace

TEST(Occlusion, BackgroundHiddenBehindABarInTheRightViewIsOccludedInTheLeftMask) {
    const std::vector<Visibility> v = visibilityInOtherView(20, 1, leftRow(), rightRow(), -1);
    for (uint32_t x = 0; x < 20; ++x) {
        const bool outside = x < 2;             // x - 2 < -0.5: left of the right image
        const bool hidden = x >= 6 && x <= 9;   // x - 2 in 4..7: the bar covers the match
        EXPECT_EQ(v[x], outside || hidden ? Visibility::Occluded : Visibility::Visible) << x;
    }
}

TEST(Occlusion, TheRightMaskLooksTheOtherWay) {
    const std::vector<Visibility> v = visibilityInOtherView(20, 1, rightRow(), leftRow(), +1);
    for (uint32_t x = 0; x < 20; ++x) {
        const bool outside = x > 17;            // x + 2 > 19.5
        const bool hidden = x >= 8 && x <= 11;  // x + 2 in 10..13: the bar covers it in the left view
        EXPECT_EQ(v[x], outside || hidden ? Visibility::Occluded : Visibility::Visible) << x;
    }
}

TEST(Occlusion, AThinBladeCoveringOneOfTheTwoCentresAroundTheMatchDoesNotHideIt) {
    std::vector<float> left(20, 2.0f), right(20, 2.0f);
    right[7] = 6.0f;   // a one-pixel blade in the right view
    left[9] = 2.5f;    // its match 6.5 lies between centres 6 (background) and 7 (blade): seen
    left[12] = 3.0f;   // match 9: the centre itself, background: seen
    right[10] = 6.0f;  // ...and left 13 (d 3, match 10, a centre covered by a blade): hidden
    left[13] = 3.0f;
    const std::vector<Visibility> v = visibilityInOtherView(20, 1, left, right, -1);
    EXPECT_EQ(v[9], Visibility::Visible);
    EXPECT_EQ(v[12], Visibility::Visible);
    EXPECT_EQ(v[13], Visibility::Occluded);
}

TEST(Occlusion, ASlantedPlaneIsVisibleAndSkyHasNoTruth) {
    // Disparity affine along the row (a plane): left d = 3 + 0.25 x; the right pixel xr sees the point of left
    // x = xr + d, so d_right(xr) = (3 + 0.25 xr) / 0.75.
    const uint32_t w = 40;
    std::vector<float> left(w), right(w);
    for (uint32_t x = 0; x < w; ++x) {
        left[x] = 3.0f + 0.25f * float(x);
        right[x] = (3.0f + 0.25f * float(x)) / 0.75f;
    }
    left[0] = 0.0f; // sky
    const std::vector<Visibility> v = visibilityInOtherView(w, 1, left, right, -1);
    EXPECT_EQ(v[0], Visibility::NoTruth);
    for (uint32_t x = 5; x < w; ++x) EXPECT_EQ(v[x], Visibility::Visible) << x; // x - d >= 0 from x = 4
    EXPECT_EQ(occlusionMaskPixels(v)[0], 0);
    EXPECT_EQ(occlusionMaskPixels(v)[10], 255);
    EXPECT_EQ(occlusionMaskPixels({Visibility::Occluded})[0], 128);
}
