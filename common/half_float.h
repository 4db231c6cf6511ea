// IEEE 754 binary16 ("half") <-> float conversion on raw bit patterns, shared by the engine (previews) and the
// Vulkan-free core.
//
// The renderer reads colour back as half bit patterns (what EXR stores); the sensor model converts them to
// float, works in float and converts back. Conversions here are exact (half -> float) and round to nearest,
// ties to even (float -> half), the IEEE default that Imath::half and hardware conversions also use, so a
// half -> float -> half round trip reproduces every pattern bit for bit.
#pragma once

#include <bit>
#include <cstdint>

namespace sward {

constexpr float halfBitsToFloat(uint16_t h) {
    uint32_t sign = uint32_t(h & 0x8000u) << 16;
    uint32_t exponent = (h >> 10) & 0x1fu;
    uint32_t mantissa = h & 0x3ffu;
    if (exponent == 0x1f) // infinity or NaN (payload kept in the top mantissa bits)
        return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));
    if (exponent == 0) {
        if (mantissa == 0) return std::bit_cast<float>(sign);
        // Subnormal half: normalise, every half subnormal is a normal float.
        exponent = 1;
        while (!(mantissa & 0x400u)) {
            mantissa <<= 1;
            --exponent;
        }
        mantissa &= 0x3ffu;
    }
    return std::bit_cast<float>(sign | ((exponent + 127 - 15) << 23) | (mantissa << 13));
}

constexpr uint16_t floatToHalfBits(float f) {
    uint32_t x = std::bit_cast<uint32_t>(f);
    uint32_t sign = (x >> 16) & 0x8000u;
    uint32_t a = x & 0x7fffffffu;
    if (a >= 0x7f800000u) { // infinity, or NaN kept quiet (a NaN must not turn into infinity)
        if (a == 0x7f800000u) return uint16_t(sign | 0x7c00u);
        return uint16_t(sign | 0x7e00u | ((a >> 13) & 0x3ffu));
    }
    // 65520 is halfway between the largest half (65504, odd mantissa) and 2^16: ties to even go up to infinity.
    if (a >= 0x477ff000u) return uint16_t(sign | 0x7c00u);
    if (a >= 0x38800000u) { // normal half range, |f| >= 2^-14
        uint32_t h = ((a >> 23) - 127 + 15) << 10 | ((a >> 13) & 0x3ffu);
        uint32_t rest = a & 0x1fffu;
        // A carry out of the mantissa correctly increments the exponent.
        if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;
        return uint16_t(sign | h);
    }
    // 2^-25 is halfway between 0 and the smallest subnormal 2^-24: ties to even give zero.
    if (a <= 0x33000000u) return uint16_t(sign);
    // Subnormal half: value = m * 2^-24. The float is m_f * 2^(e - 150) with the implicit bit set.
    uint32_t m = (a & 0x7fffffu) | 0x800000u;
    uint32_t shift = 126 - (a >> 23); // 14 .. 24
    uint32_t h = m >> shift;
    uint32_t rest = m & ((1u << shift) - 1);
    uint32_t halfway = 1u << (shift - 1);
    if (rest > halfway || (rest == halfway && (h & 1u))) ++h; // may carry into the smallest normal: correct
    return uint16_t(sign | h);
}

} // namespace sward
