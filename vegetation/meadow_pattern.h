// Field-scale structure of a meadow (issue 47): patches where a category grows denser or thinner (down to bare
// spots), taller and shorter stretches, and tussocks: plants gathered around clump centres instead of a uniform
// jittered spread. Without it every plant is a separate tuft at uniform size and spacing.
//
// Every term is a pure function of the vegetation seed, the category and the WORLD position (never the tile or the
// field), so a world's tiles meet without a seam and any field can be regenerated alone. Only + - * / floor are used
// (common/noise.h), as in placement.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace sward {

// vegetation.pattern (docs/scene-format.md); every strength 0 (the default) leaves placement as the map alone.
struct MeadowPattern {
    float patchSize = 8.0f;      // metres: the feature size of the patches
    float patchiness = 0.0f;     // 0..1: density contrast between patches; from about 0.5 on, bare spots appear
    float heightGradient = 0.0f; // 0..0.9: relative height change between patches (taller where denser)
    float clumping = 0.0f;       // 0..0.9: how far each plant is pulled toward its tussock's centre
    float clumpSize = 0.5f;      // metres: tussock spacing

    bool active() const { return patchiness > 0.0f || heightGradient > 0.0f || clumping > 0.0f; }
};

// The patch noise of `category` at world (x, y): in [0, 1], mean about 0.5; two octaves of value noise.
double patchNoise(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y);

// Factor on the map's density of `category` at world (x, y): 1 + 4 patchiness (n - 1/2), clipped at 0 (bare).
double patchDensityFactor(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y);

// Factor on a plant's height at world (x, y): 1 + heightGradient (2 n - 1), n the category's patch noise, so
// plants stand taller where they grow denser.
double patchHeightFactor(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y);

// Where a plant placed at world (x, y) stands after the pull toward its tussock: the centre of the clump cell
// holding (x, y) (a jittered lattice of clumpSize, one per category) approached by the fraction `clumping`.
glm::dvec2 clumpPosition(const MeadowPattern& pattern, uint64_t seed, uint32_t category, double x, double y);

} // namespace sward
