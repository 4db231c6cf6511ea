// Counter-based hashing: the only source of randomness in sward.
//
// Every random quantity is a pure function of a key (seed, tile, field, cluster, sample, ...), so any part of a
// scene can be regenerated alone, in any order and on any number of threads, with bitwise identical results.
// Never use std:: distributions or rand(): their sequences depend on call order and on the standard library.
#pragma once

#include "common/exact_math.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace sward {

// splitmix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

// Hash of an ordered key. Each component is folded in with a distinct odd constant so (a, b) != (b, a).
constexpr uint64_t hashKey(std::initializer_list<uint64_t> key) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (uint64_t k : key) h = mix64(h ^ (k + 0x632be59bd9b4e019ull + (h << 6)));
    return h;
}

// Uniform float in [0, 1) from the top 24 bits: exactly representable, identical on every machine.
constexpr float unitFloat(uint64_t h) {
    return float(uint32_t(h >> 40)) * (1.0f / 16777216.0f);
}

// Uniform double in [0, 1) from the top 53 bits.
constexpr double unitDouble(uint64_t h) {
    return double(h >> 11) * (1.0 / 9007199254740992.0);
}

// Standard normal from one hash: Box-Muller on two uniforms derived from it (u1 in (0, 1], so the logarithm is finite),
// with the logarithm and the cosine of common/exact_math.h, not libm's: the same bits on every machine.
inline double standardNormal(uint64_t h) {
    const double u1 = 1.0 - unitDouble(h);
    const double u2 = unitDouble(mix64(h ^ 0x2545f4914f6cdd1dull));
    return std::sqrt(-2.0 * 0.69314718055994530942 * exactLog2(u1)) * exactCosTwoPi(u2);
}

// A stream of independent values under one key: value i of the stream is hashKey({key, i}).
struct HashStream {
    uint64_t key;
    uint64_t next = 0;
    constexpr uint64_t nextU64() { return mix64(key ^ mix64(++next * 0xd1342543de82ef95ull)); }
    constexpr float nextFloat() { return unitFloat(nextU64()); }
};

} // namespace sward
