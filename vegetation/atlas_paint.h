// The atlas painter's tools (internal to vegetation/atlas_paint.cpp and atlas_plants.cpp): strokes, per-cell
// dice and the shapes the plant painters are built from. Every plant part is a stroke, a polyline with a
// half-width per point, rasterised with analytic one-texel edge coverage (the soft alpha at blade edges that
// alpha-to-coverage turns into smooth silhouettes).
#pragma once

#include "common/hash.h"
#include "vegetation/atlas_colour.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

namespace sward::atlas_detail {

using glm::vec2;
using glm::vec3;
using glm::vec4;

inline constexpr float kPi = std::numbers::pi_v<float>;

// Palette entries are albedos in linear RGB (reflectance averaged over each sRGB primary's band), the way
// leaf and canopy spectra are measured; the painter works in linear light and encodes to sRGB at the end.
inline vec3 albedo(float r, float g, float b) {
    return {r, g, b};
}

struct Stroke {
    std::vector<vec2> points; // centreline in cell texels (y down), from the attached end
    std::vector<float> halfWidths;
    vec3 base{0.0f}, tip{0.0f}; // linear colour at the attached end and at the free end
    float tipStart = 1.0f;      // fraction of the length where the colour starts turning to `tip`
    float shadeBase = 0.0f;     // darkening at the attached end: self-shadowing deep inside a clump
    // Interior texture stays low in contrast: a real leaf's fold and midrib differ from its blade by a few per
    // cent of albedo, and strong interior lines made every tuft evenly crisp (issue 47: FAST 46,000 per MP).
    float sideShade = 0.05f; // one half darker than the other: reads as a folded blade or leaf
    float midrib = 0.0f;     // lighter centre line
};

inline float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

inline vec2 direction(float angleFromUp) {
    return {std::sin(angleFromUp), -std::cos(angleFromUp)};
}

inline std::vector<vec2> cubicBezier(vec2 p0, vec2 p1, vec2 p2, vec2 p3, int count) {
    std::vector<vec2> points(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        const float t = float(i) / float(count - 1), u = 1.0f - t;
        points[size_t(i)] = u * u * u * p0 + 3.0f * u * u * t * p1 + 3.0f * u * t * t * p2 + t * t * t * p3;
    }
    return points;
}

// Point and unit tangent at fraction t of a polyline's vertex sequence (vertices roughly evenly spaced).
inline std::pair<vec2, vec2> alongPolyline(const std::vector<vec2>& points, float t) {
    const float f = std::clamp(t, 0.0f, 1.0f) * float(points.size() - 1);
    const size_t i = std::min(size_t(f), points.size() - 2);
    const vec2 a = points[i], b = points[i + 1];
    return {a + (b - a) * (f - float(i)), glm::normalize(b - a)};
}

inline vec2 rotate(vec2 v, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// Random numbers for one cell, drawn from a HashStream so a cell is a pure function of (seed, row kind, column).
struct Dice {
    HashStream stream;
    float operator()() { return stream.nextFloat(); }
    float range(float lo, float hi) { return lo + (hi - lo) * stream.nextFloat(); }
    float centred() { return stream.nextFloat() + stream.nextFloat() - 1.0f; } // triangular in (-1, 1)
    // Value varies by +-amount, hue by a few per cent per channel (one blade or leaf against its neighbour).
    vec3 jitter(vec3 c, float amount) {
        const float k = range(1.0f - amount, 1.0f + amount);
        return glm::clamp(c * k * vec3(range(0.95f, 1.05f), range(0.95f, 1.05f), range(0.95f, 1.05f)), 0.0f, 1.0f);
    }
    size_t pick(size_t count) { return std::min(size_t(stream.nextFloat() * float(count)), count - 1); }
};

// Half-width profiles over t in [0, 1].
inline float bladeProfile(float t) {
    return (1.0f - 0.3f * t) * std::pow(std::min(1.0f, (1.0f - t) * 2.2f), 0.9f);
}
inline float leafProfile(float t) {
    return std::pow(std::sin(kPi * std::clamp(t, 0.0f, 1.0f)), 0.7f);
}

template <class Profile> std::vector<float> widths(size_t count, float halfWidth, Profile profile) {
    std::vector<float> w(count);
    for (size_t i = 0; i < count; ++i) w[i] = halfWidth * profile(float(i) / float(count - 1));
    return w;
}

// A leaf from `from` along `dir` (unit), drooping by `droop` times its length at the tip.
inline Stroke leaf(vec2 from, vec2 dir, float length, float halfWidth, float droop, vec3 base, vec3 tip) {
    Stroke s{.base = base, .tip = tip, .tipStart = 0.3f, .sideShade = 0.07f, .midrib = 0.04f};
    for (int i = 0; i < 8; ++i) {
        const float t = float(i) / 7.0f;
        s.points.push_back(from + dir * (length * t) + vec2(0.0f, droop * length * t * t));
    }
    s.halfWidths = widths(8, halfWidth, leafProfile);
    return s;
}

// A round dot (flower floret, berry, flower disc): a very short stroke.
inline Stroke dot(vec2 centre, float radius, vec3 colour, float squash = 1.0f) {
    const float dx = radius * (1.0f - squash);
    return {.points = {centre - vec2(dx, 0.0f), centre + vec2(dx, 0.0f)},
            .halfWidths = {radius * squash, radius * squash},
            .base = colour,
            .tip = colour,
            .sideShade = 0.08f};
}

using Plant = std::vector<Stroke>;

// The painters of the three plant kinds (atlas_plants.cpp): one plant of `variant` in an S x S texel cell.
Plant paintGrass(Dice& dice, float S, uint32_t variant);
Plant paintFerns(Dice& dice, float S, uint32_t variant);
Plant paintFlowers(Dice& dice, float S, uint32_t variant);

} // namespace sward::atlas_detail
