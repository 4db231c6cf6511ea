// Elementary functions by + - * /, frexp and ldexp only, so they give the same bits on every machine and C library
// (libm's log, exp and cos may differ in the last place between versions): for anything hashed noise or an exposure
// feeds into an image that must be bitwise reproducible.
#pragma once

#include <cmath>

namespace sward {

// 2^x (|x| <= 64; within a few ulp of std::exp2).
inline double exactExp2(double x) {
    // 2^x = 2^n 2^f with n = floor(x), f in [0, 1); 2^f = e^(f ln 2) by its Taylor series (terms below 1e-17 after 18).
    const double n = std::floor(x), t = (x - n) * 0.69314718055994530942;
    double sum = 1.0, term = 1.0;
    for (int k = 1; k <= 18; ++k) {
        term = term * t / double(k);
        sum += term;
    }
    return std::ldexp(sum, int(n));
}

// log2(x) for finite x > 0 (within 4e-15 of std::log2).
inline double exactLog2(double x) {
    // x = m 2^e with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(z), z = (m - 1) / (m + 1), |z| < 0.172: 12 odd terms
    // of the series leave less than 1e-19.
    int e = 0;
    double m = std::frexp(x, &e); // [0.5, 1)
    if (m < 0.70710678118654752440) {
        m *= 2.0;
        --e;
    }
    const double z = (m - 1.0) / (m + 1.0), z2 = z * z;
    double sum = 0.0, power = z;
    for (int k = 0; k < 12; ++k) {
        sum += power / double(2 * k + 1);
        power *= z2;
    }
    return double(e) + 2.0 * sum * 1.44269504088896340736; // log2(e)
}

// cos(2 pi u) for u in [0, 1] (within 1e-15 of std::cos): u reduced to the nearest quarter turn k / 4, then the
// Taylor series of cos or sin on |x| <= pi / 4 (the first omitted terms below 1e-17).
inline double exactCosTwoPi(double u) {
    const double k = std::floor(4.0 * u + 0.5);
    const double x = (u - 0.25 * k) * 6.28318530717958647693, x2 = x * x;
    double c = 1.0, s = x, cTerm = 1.0, sTerm = x;
    for (int n = 1; n <= 9; ++n) {
        cTerm *= -x2 / double((2 * n - 1) * (2 * n));
        sTerm *= -x2 / double((2 * n) * (2 * n + 1));
        c += cTerm;
        s += sTerm;
    }
    switch (int(k) & 3) {
    case 0:
        return c;
    case 1:
        return -s;
    case 2:
        return -c;
    default:
        return s;
    }
}

} // namespace sward
