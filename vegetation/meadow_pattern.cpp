#include "vegetation/meadow_pattern.h"

#include "common/hash.h"
#include "common/noise.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

// Noise layers of common/noise.h, apart from the terrain's and the grass maps' (which use 0..15).
constexpr uint32_t kPatchLayer = 0x5a00;
constexpr uint64_t kClumpSalt = 0x636c756d70ull; // "clump"

} // namespace

double patchNoise(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y) {
    const double s = 1.0 / pattern.patchSize;
    const double coarse = valueNoise(seed, kPatchLayer + 2 * category, x * s, y * s);
    const double fine = valueNoise(seed, kPatchLayer + 2 * category + 1, x * s * 2.3, y * s * 2.3);
    return std::clamp(0.5 + 0.5 * (0.7 * coarse + 0.45 * fine), 0.0, 1.0);
}

double patchDensityFactor(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y) {
    if (pattern.patchiness <= 0.0f) return 1.0;
    const double n = patchNoise(pattern, seed, category, x, y);
    return std::max(0.0, 1.0 + 4.0 * double(pattern.patchiness) * (n - 0.5));
}

double patchHeightFactor(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y) {
    if (pattern.heightGradient <= 0.0f) return 1.0;
    return 1.0 + double(pattern.heightGradient) * (2.0 * patchNoise(pattern, seed, category, x, y) - 1.0);
}

glm::dvec2 clumpPosition(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y) {
    if (pattern.clumping <= 0.0f) return {x, y};
    const double size = pattern.clumpSize;
    const double cx = std::floor(x / size), cy = std::floor(y / size);
    const uint64_t h = hashKey({seed, kClumpSalt, category, uint64_t(int64_t(cx)), uint64_t(int64_t(cy))});
    // The centre stays in the cell's middle 70 %, so neighbouring tussocks never merge into one.
    const glm::dvec2 centre((cx + 0.15 + 0.7 * unitDouble(h)) * size,
                            (cy + 0.15 + 0.7 * unitDouble(mix64(h ^ 0x9e3779b97f4a7c15ull))) * size);
    return glm::dvec2(x, y) + double(pattern.clumping) * (centre - glm::dvec2(x, y));
}

} // namespace sward
