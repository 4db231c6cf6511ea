// The one snorm packing: the records, the collision pass and the recovery reference share it.
#include "common/snorm.h"

#include <gtest/gtest.h>

#include <cstdint>

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
