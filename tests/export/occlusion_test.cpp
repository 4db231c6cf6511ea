// Occlusion from the left disparity: a near surface hides what lies behind it in the right view.
#include "export/occlusion.h"

#include <gtest/gtest.h>

using namespace sward;

TEST(Occlusion, BackgroundBehindANearBarIsOccludedOnItsLeftSide) {
    // One row: background at 2 px everywhere, a bar at 6 px over x = 10..13. In the right view the bar lands on
    // columns 4..7 and covers the background pixels that land there: x = 6..9 (x - 2 in 4..7).
    const uint32_t w = 20;
    std::vector<float> d(w, 2.0f);
    for (uint32_t x = 10; x < 14; ++x) d[x] = 6.0f;
    const std::vector<Visibility> v = leftVisibility(w, 1, d);
    for (uint32_t x = 0; x < w; ++x) {
        const bool outside = x < 2; // x - 2 < -0.5: the match is left of the right image
        const bool hidden = x >= 6 && x <= 9;
        EXPECT_EQ(v[x], outside || hidden ? Visibility::Occluded : Visibility::Visible) << x;
    }
}

TEST(Occlusion, PixelsWithoutTruthStayWithoutTruthAndDoNotOcclude) {
    std::vector<float> d = {0.0f, 0.0f, 1.0f, 1.0f};
    const std::vector<Visibility> v = leftVisibility(4, 1, d);
    EXPECT_EQ(v[0], Visibility::NoTruth);
    EXPECT_EQ(v[1], Visibility::NoTruth);
    EXPECT_EQ(v[2], Visibility::Visible);
    EXPECT_EQ(v[3], Visibility::Visible);
}

TEST(Occlusion, ASlantedSurfaceDoesNotOccludeItself) {
    // Disparity growing by 0.6 px per pixel (a steep slant): neighbours collide on right columns, but within the
    // tolerance.
    const uint32_t w = 30;
    std::vector<float> d(w);
    for (uint32_t x = 0; x < w; ++x) d[x] = 1.0f + 0.6f * float(x) / 2.0f;
    const std::vector<Visibility> v = leftVisibility(w, 1, d);
    for (uint32_t x = 2; x < w; ++x) EXPECT_EQ(v[x], Visibility::Visible) << x;
}
