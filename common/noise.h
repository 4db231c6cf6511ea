// Hashed value noise, the deterministic building block of procedural terrain and grass maps.
// Uses only + - * and floor (no libm transcendentals), so results are bitwise identical on every x86-64 machine.
#pragma once

#include "common/hash.h"

#include <cmath>
#include <cstdint>

namespace sward {

// C2-continuous fade 6t^5 - 15t^4 + 10t^3, so the noise has no visible grid creases.
inline double quinticFade(double t) {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Random value in [-1, 1) at integer lattice point (x, y) of one noise layer.
inline double latticeValue(uint64_t seed, uint32_t layer, int64_t x, int64_t y) {
    return unitDouble(hashKey({seed, layer, uint64_t(x), uint64_t(y)})) * 2.0 - 1.0;
}

// Value noise in [-1, 1] with unit lattice spacing; layer selects an independent noise.
inline double valueNoise(uint64_t seed, uint32_t layer, double x, double y) {
    double fx = std::floor(x), fy = std::floor(y);
    int64_t ix = int64_t(fx), iy = int64_t(fy);
    double u = quinticFade(x - fx), v = quinticFade(y - fy);
    double a = latticeValue(seed, layer, ix, iy), b = latticeValue(seed, layer, ix + 1, iy);
    double c = latticeValue(seed, layer, ix, iy + 1), d = latticeValue(seed, layer, ix + 1, iy + 1);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

} // namespace sward
