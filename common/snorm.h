// Signed normalised integers as the plant records store them (shaders/shared/plant_decode.glsl, recovery.glsl):
// a value clamped to [-1, 1], times the largest code 2^(bits-1) - 1, rounded half away from zero, stored as two's
// complement in the low `bits` bits. The one C++ definition; the shaders mirror it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

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
