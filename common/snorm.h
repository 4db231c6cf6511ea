// Signed normalised integers as the plant records store them (shaders/shared/plant_decode.glsl, recovery.glsl):
// a value clamped to [-1, 1], times the largest code 2^(bits-1) - 1, rounded half away from zero, stored as two's
// complement in the low `bits` bits. The one C++ definition; the shaders mirror it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sward {

// Round half away from zero. Truncating a non-negative float is floor, and a cast compiles to one instruction
// where std::floor is a libm call on baseline x86-64; both are exact, so results are identical everywhere. Adding
// the half with v's sign gives the shaders' v >= 0 ? int(v + 0.5) : -int(-v + 0.5) bit for bit (negation and
// round-to-nearest are symmetric, truncation is toward zero) without a branch, which random signs mispredict.
inline int32_t roundHalfAway(float v) {
    return int32_t(v + std::copysign(0.5f, v));
}

// The largest code of a `bits`-bit snorm (32767 for 16 bits, 511 for 10), exact as a float. 2 <= bits <= 24.
constexpr float snormScale(uint32_t bits) {
    return float((1u << (bits - 1)) - 1u);
}

// v as a `bits`-bit snorm in the low bits of the result (the other bits zero).
inline uint32_t packSnorm(float v, uint32_t bits) {
    return uint32_t(roundHalfAway(std::clamp(v, -1.0f, 1.0f) * snormScale(bits))) & ((1u << bits) - 1u);
}

// Two values as 16-bit snorms, x in the low half: packSnorm(x, 16) | packSnorm(y, 16) << 16, bit for bit, both lanes
// at once where there is SSE2. The collision pass packs a push per contact, and the scalar clamps, sign copies and
// conversions were a third of writing one.
inline uint32_t packSnorm2x16(float x, float y) {
#if defined(__SSE2__)
    // std::clamp(v, -1, 1): maxps / minps return their second operand on a tie, the same value.
    const __m128 v = _mm_min_ps(_mm_set1_ps(1.0f), _mm_max_ps(_mm_set1_ps(-1.0f), _mm_setr_ps(x, y, 0.0f, 0.0f)));
    const __m128 scaled = _mm_mul_ps(v, _mm_set1_ps(snormScale(16)));
    const __m128 half = _mm_or_ps(_mm_and_ps(scaled, _mm_set1_ps(-0.0f)), _mm_set1_ps(0.5f)); // copysign(0.5, v)
    const __m128i codes = _mm_and_si128(_mm_cvttps_epi32(_mm_add_ps(scaled, half)), _mm_set1_epi32(0xffff));
    return uint32_t(_mm_cvtsi128_si32(codes)) | uint32_t(_mm_cvtsi128_si32(_mm_srli_si128(codes, 4))) << 16;
#else
    return packSnorm(x, 16) | (packSnorm(y, 16) << 16);
#endif
}

// How a decoder turns a code into a value. The two differ in the last bit for some codes (1536 of the 65536
// 16-bit ones), and both are needed: plant_decode.glsl, which the renderer and the record tests follow,
// divides; recovery.glsl must give the same bits on every Vulkan device, where division is not correctly rounded
// (multiplication is), so it and its C++ twin multiply by the rounded reciprocal.
enum class SnormDivide { Exact, ByReciprocal };

// The value of the `bits`-bit snorm in the low bits of `packed` (higher bits ignored), in [-1, 1].
inline float unpackSnorm(uint32_t packed, uint32_t bits, SnormDivide divide) {
    const int32_t code = int32_t(packed << (32 - bits)) >> (32 - bits); // sign-extends the low `bits` bits
    const float scaled = divide == SnormDivide::Exact ? float(code) / snormScale(bits)
                                                      : float(code) * (1.0f / snormScale(bits));
    return std::max(scaled, -1.0f);
}

} // namespace sward
