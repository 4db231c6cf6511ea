// The one snorm packing: the records, the collision pass and the recovery reference share it.
#include "common/snorm.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace sward;

TEST(Snorm, PacksWithRoundingHalfAwayFromZeroAndClamps) {
    EXPECT_EQ(packSnorm(0.0f, 16), 0u);
    EXPECT_EQ(packSnorm(1.0f, 16), 32767u);
    EXPECT_EQ(packSnorm(2.0f, 16), 32767u);
    EXPECT_EQ(packSnorm(-1.0f, 16), 0x8001u);
    EXPECT_EQ(packSnorm(-5.0f, 10), 0x201u);
    EXPECT_EQ(packSnorm(0.5f / 511.0f, 10), 1u) << "half a step rounds away from zero";
    EXPECT_EQ(packSnorm(-0.5f / 511.0f, 10), 0x3ffu) << "half a step rounds away from zero";
    EXPECT_EQ(roundHalfAway(2.5f), 3);
    EXPECT_EQ(roundHalfAway(-2.5f), -3);
}

// roundHalfAway adds a signed half without branching; recovery.glsl branches on the sign. They must agree bitwise,
// above all at and next to the halves, and on both zeros.
TEST(Snorm, RoundingEqualsTheShadersBranchingFormAtEveryHalfAndBetween) {
    auto shaders = [](float x) { return x >= 0.0f ? int32_t(x + 0.5f) : -int32_t(-x + 0.5f); };
    EXPECT_EQ(roundHalfAway(-0.0f), 0);
    EXPECT_EQ(roundHalfAway(0.0f), 0);
    for (int32_t k = -40000; k <= 40000; ++k) {
        const float half = float(k) + 0.5f;
        for (float v : {half, std::nextafter(half, -1e9f), std::nextafter(half, 1e9f), float(k),
                        std::nextafter(float(k), -1e9f), std::nextafter(float(k), 1e9f)})
            ASSERT_EQ(roundHalfAway(v), shaders(v)) << v;
    }
    for (uint32_t bits = 0; bits < 0x47800000u; bits += 4099) // every magnitude below 65536, both signs
        for (float v : {std::bit_cast<float>(bits), -std::bit_cast<float>(bits)})
            ASSERT_EQ(roundHalfAway(v), shaders(v)) << v;
}

TEST(Snorm, EveryCodeRoundTripsInBothDivisionModes) {
    for (uint32_t bits : {10u, 16u}) {
        for (uint32_t code = 0; code < (1u << bits); ++code) {
            if (code == (1u << (bits - 1))) continue; // the code below -1 decodes to -1, as on the GPU
            for (SnormDivide divide : {SnormDivide::Exact, SnormDivide::ByReciprocal})
                ASSERT_EQ(packSnorm(unpackSnorm(code, bits, divide), bits), code) << bits << " bits, code " << code;
        }
        EXPECT_EQ(unpackSnorm(1u << (bits - 1), bits, SnormDivide::Exact), -1.0f);
        EXPECT_EQ(unpackSnorm(0xffff0000u | 1u, bits, SnormDivide::Exact), 1.0f / snormScale(bits))
            << "bits above `bits` are ignored";
    }
}

TEST(Snorm, TheTwoDivisionModesDifferInTheLastBitForSomeCodes) {
    uint32_t differ = 0;
    for (uint32_t code = 0; code < 65536; ++code)
        differ += unpackSnorm(code, 16, SnormDivide::Exact) != unpackSnorm(code, 16, SnormDivide::ByReciprocal);
    EXPECT_GT(differ, 0u) << "if they never differed, one mode would be enough";
}

// The two-lane packing (SSE2 where there is SSE2) gives the scalar packing's bits for every value: both zeros, the
// halves, the clamp's edges, out of range and infinities (not NaN: the scalar's conversion of NaN to an integer is
// undefined, and no caller packs one).
TEST(Snorm, TwoLanePackingEqualsTheScalarPacking) {
    auto scalar = [](float x, float y) { return packSnorm(x, 16) | (packSnorm(y, 16) << 16); };
    std::vector<float> values = {0.0f,
                                 -0.0f,
                                 1.0f,
                                 -1.0f,
                                 2.0f,
                                 -2.0f,
                                 INFINITY,
                                 -INFINITY,
                                 std::nextafter(1.0f, 2.0f),
                                 std::nextafter(-1.0f, -2.0f)};
    for (int32_t k = -32767; k <= 32767; ++k) {
        const float half = (float(k) + 0.5f) / snormScale(16);
        values.insert(values.end(), {half, std::nextafter(half, -2.0f), std::nextafter(half, 2.0f)});
    }
    for (size_t i = 0; i < values.size(); ++i) {
        const float x = values[i], y = values[(i * 7919 + 13) % values.size()];
        ASSERT_EQ(packSnorm2x16(x, y), scalar(x, y)) << x << ", " << y;
    }
    for (uint32_t bits = 0; bits <= 0x7f800000u; bits += 65521) // every magnitude up to infinity, both signs
        for (float v : {std::bit_cast<float>(bits), -std::bit_cast<float>(bits)})
            ASSERT_EQ(packSnorm2x16(v, -v), scalar(v, -v)) << v;
}
