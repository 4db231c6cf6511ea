#include "common/half_float.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

using namespace sward;

// Every one of the 65536 half patterns survives half -> float -> half bit for bit (NaNs stay NaN).
TEST(Half, RoundTripsAllPatterns) {
    for (uint32_t h = 0; h < 65536; ++h) {
        float f = halfBitsToFloat(uint16_t(h));
        bool nan = (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu) != 0;
        if (nan) {
            ASSERT_TRUE(std::isnan(f)) << h;
            uint16_t back = floatToHalfBits(f);
            ASSERT_TRUE((back & 0x7c00u) == 0x7c00u && (back & 0x3ffu) != 0) << h;
            ASSERT_EQ(back & 0x8000u, h & 0x8000u) << h;
        } else {
            ASSERT_EQ(floatToHalfBits(f), h) << h;
        }
    }
}

#if defined(__FLT16_MAX__)
// The compiler's _Float16 (IEEE binary16, round to nearest even) is an independent reference.
TEST(Half, DecodesLikeFloat16ForAllPatterns) {
    for (uint32_t h = 0; h < 65536; ++h) {
        float expected = float(std::bit_cast<_Float16>(uint16_t(h)));
        float f = halfBitsToFloat(uint16_t(h));
        if (std::isnan(expected))
            ASSERT_TRUE(std::isnan(f)) << h;
        else
            ASSERT_EQ(std::bit_cast<uint32_t>(f), std::bit_cast<uint32_t>(expected)) << h;
    }
}

// Rounding of floats between halves: every midpoint and its float neighbours for all finite halves, plus a
// sweep over the whole float range with a stride that visits every exponent and many mantissas.
TEST(Half, RoundsToNearestEvenLikeFloat16) {
    auto check = [](float f) {
        uint16_t expected = std::bit_cast<uint16_t>(_Float16(f));
        uint16_t got = floatToHalfBits(f);
        if (std::isnan(f))
            ASSERT_TRUE((got & 0x7c00u) == 0x7c00u && (got & 0x3ffu) != 0);
        else
            ASSERT_EQ(got, expected) << "float bits " << std::bit_cast<uint32_t>(f);
    };
    for (uint32_t h = 0; h < 0x7c00u; ++h) {
        for (uint32_t sign : {0u, 0x8000u}) {
            float a = halfBitsToFloat(uint16_t(h | sign)), b = halfBitsToFloat(uint16_t((h + 1) | sign));
            float mid = float((double(a) + double(b)) * 0.5); // exact: halves have 11 significant bits
            check(mid);
            check(std::nextafter(mid, 0.0f));
            check(std::nextafter(mid, 2.0f * mid));
        }
    }
    for (float f : {65504.0f, 65519.99f, 65520.0f, 65535.0f, 65536.0f, 1e-8f, 2.9802322e-8f, 5.9604645e-8f})
        for (float signedF : {f, -f}) check(signedF);
    for (uint64_t bits = 0; bits < (1ull << 32); bits += 4093) check(std::bit_cast<float>(uint32_t(bits)));
}
#endif
