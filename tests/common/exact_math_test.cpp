// common/exact_math.h: libm-free elementary functions, and the standard normal built on them (common/hash.h).
#include "common/exact_math.h"
#include "common/hash.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace sward;

TEST(ExactMath, CosineOfATurnFollowsLibmWithin1e15) {
    EXPECT_EQ(exactCosTwoPi(0.0), 1.0);
    EXPECT_EQ(exactCosTwoPi(0.5), -1.0);
    EXPECT_EQ(exactCosTwoPi(1.0), 1.0);
    double worst = 0.0;
    for (int i = 0; i <= 100000; ++i) {
        const double u = i / 100000.0 + 1e-7 * (i % 7);
        worst = std::max(worst, std::abs(exactCosTwoPi(u) - std::cos(2.0 * std::numbers::pi * u)));
    }
    EXPECT_LT(worst, 1e-15);
}

TEST(ExactMath, StandardNormalHasUnitVarianceAndNormalTails) {
    double sum = 0.0, squares = 0.0, fourth = 0.0;
    uint32_t beyond2 = 0;
    const uint32_t n = 400000;
    for (uint32_t i = 0; i < n; ++i) {
        const double z = standardNormal(hashKey({7, i}));
        sum += z, squares += z * z, fourth += z * z * z * z;
        beyond2 += std::abs(z) > 2.0;
    }
    EXPECT_NEAR(sum / n, 0.0, 0.005);
    EXPECT_NEAR(squares / n, 1.0, 0.01);
    EXPECT_NEAR(fourth / n, 3.0, 0.06);              // a normal's kurtosis
    EXPECT_NEAR(double(beyond2) / n, 0.0455, 0.002); // P(|z| > 2)
    // The same as Box-Muller through libm to rounding: only the last bits may differ, never the distribution.
    const uint64_t h = hashKey({11, 3});
    const double u1 = 1.0 - unitDouble(h), u2 = unitDouble(mix64(h ^ 0x2545f4914f6cdd1dull));
    EXPECT_NEAR(standardNormal(h), std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2), 1e-14);
}
