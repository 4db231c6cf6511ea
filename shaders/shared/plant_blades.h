// Near plants as blade geometry (LodParams::nearBlades, VegetationConstants::options.y): each near plant of a grass
// category drawn as opaque, tapered, curved strips instead of its four alpha-tested cards. A CPU driver cannot test
// depth before a fragment shader that may discard, so through dense cards it shades every hidden layer; opaque
// blades are depth-tested first and shade about one layer. The same text is GLSL and C++: plant_blades.glsl (the
// draws and the bake) and vegetation/expansion_reference.cpp (the CPU mirror) place the very same points.
//
// Every blade is a pure function of the plant's expanded record: its root spread around the plant's base, heading,
// lean, curl, length and width come from the plant's key (bladeKey) and the blade's number; the wind's and the
// interaction's tip bends it by quadPoint's law (plant_vertex.glsl), and a felled plant's blades lie fanned along
// its lay direction as its felled cards do.
#ifndef SWARD_PLANT_BLADES_H
#define SWARD_PLANT_BLADES_H

#include "gpu_layout.h"

#ifdef __cplusplus
#include <cmath>
namespace sward::gpu {
using vec3 = glm::vec3;
using glm::cross;
using glm::dot;
using glm::normalize;
using std::cos;
using std::sin;
#define SWARD_BLADE_FUNCTION inline
#define SWARD_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_BLADE_FUNCTION
#define SWARD_CONST(type, name, value) const type name = value
#endif

SWARD_CONST(uint, kMaxNearBlades, 32u);
// Segments along a blade. Its vertices: level k's left (2k) and right (2k + 1) edge for k < kBladeSegments, then the
// tip (2 kBladeSegments); triangles (2k, 2k + 1, 2k + 2) and (2k + 1, 2k + 3, 2k + 2) per segment but the last,
// which is the one triangle (2k, 2k + 1, tip).
SWARD_CONST(uint, kBladeSegments, 3u);
SWARD_CONST(uint, kBladeVertices, 2u * kBladeSegments + 1u);
SWARD_CONST(uint, kBladeIndices, 6u * kBladeSegments - 3u);
// A blade's base width, per card width (the plant's height times its cell's aspect) and per blade count: n blades of
// a plant together are kBladeWidth card widths wide at their bases, so the tuft covers about what its cards did.
SWARD_CONST(float, kBladeWidth, 1.2);
// The blades' roots lie within this many card widths of the plant's base.
SWARD_CONST(float, kBladeSpread, 0.3);
// Salt of the blades' hashes (SHA-256's sixth initial word, as plantHash's salts).
SWARD_CONST(uint, kBladeSalt, 0x9B05688Cu ^ 0x510E527Fu);

// Vertex number of index k of a plant's blade draw (the index buffer's pattern; blade k / kBladeIndices).
#ifdef __cplusplus
constexpr
#endif
uint bladeIndex(uint k) {
    uint blade = k / kBladeIndices, t = (k % kBladeIndices) / 3u, c = k % 3u, level = t / 2u;
    uint second = c == 0u ? 2u * level + 1u : c == 1u ? 2u * level + 3u : 2u * level + 2u;
    uint v = (t & 1u) == 0u ? 2u * level + c : second;
    return blade * kBladeVertices + v;
}

// The plant's blade key: its attributes' category, variant, orientation and random bytes with its up vector, both
// integers of the expanded record (bitwise the same on every device and on the CPU).
#ifdef __cplusplus
constexpr
#endif
uint bladeKey(uint attributes, uint up) {
    return pcgHash((attributes & 0xffffffu) ^ pcgHash(up ^ kBladeSalt));
}

// One blade's frame and size.
struct BladeShape {
    vec3 root, rise, outward, side; // root on the ground, unit axis, unit horizontal heading, up x outward
    float reach, curl, width;       // length in metres; curl: the tip's outward droop per length; width at the root
};

// Blade `blade` of `blades` of a plant at `base` with unit `up`, `height` and card width `cardWidth`, orientation
// `orientation` (radians), key `key` (bladeKey), tip offset `tip` (plant heights; a felled plant's lay direction).
SWARD_BLADE_FUNCTION BladeShape bladeShape(vec3 base, vec3 up, float height, float cardWidth, float orientation,
                                           uint key, uint blade, uint blades, bool felled, vec2 tip) {
    uint h = pcgHash(key ^ (blade * 0x9E3779B9u));
    float r0 = unitFromHash(h);
    h = pcgHash(h);
    float r1 = unitFromHash(h);
    h = pcgHash(h);
    float r2 = unitFromHash(h);
    h = pcgHash(h);
    float r3 = unitFromHash(h);
    h = pcgHash(h);
    float r4 = unitFromHash(h);
    BladeShape s;
    vec2 heading;
    if (felled) { // fanned evenly along the lay direction, as felledQuad fans the cards
        vec2 lay = dot(tip, tip) > 1e-8f ? normalize(tip) : vec2(cos(orientation), sin(orientation));
        float spread = kFelledSpread * ((2.0f * float(blade) + 1.0f) / float(blades) - 1.0f);
        heading = lay * cos(spread) + vec2(-lay.y, lay.x) * sin(spread);
    } else { // golden-angle turns between blades: evenly around the tuft whatever their number
        float angle = orientation + 2.3999632f * float(blade) + 0.8f * (r0 - 0.5f);
        heading = vec2(cos(angle), sin(angle));
    }
    vec3 horizontal = vec3(heading.x, heading.y, 0.0f);
    s.outward = normalize(horizontal - up * dot(horizontal, up));
    s.side = cross(up, s.outward);
    s.root = base + s.outward * (cardWidth * kBladeSpread * r1);
    s.rise = felled ? normalize(up * cos(kFelledLean) + s.outward * sin(kFelledLean))
                    : normalize(up + s.outward * (0.05f + 0.45f * r2));
    s.reach = height * (0.7f + 0.3f * r3);
    s.curl = felled ? 0.0f : 0.15f + 0.5f * r4;
    s.width = cardWidth * kBladeWidth / float(blades) * (0.7f + 0.6f * r1 * r3);
    return s;
}

// The height fraction of blade `s`'s level `level` (0 root .. kBladeSegments tip) for a plant `height` high: the
// level rises `along` metres along the blade, a fraction along / height (quadPoint's fraction).
SWARD_BLADE_FUNCTION float bladeFraction(BladeShape s, uint level, float height) {
    return s.reach * (float(level) / float(kBladeSegments)) / max(height, 1e-6f);
}

// The point of blade `s` at level `level` on its left (edge 0) or right (edge 1) edge, its width scaled by
// `widthScale` (the LOD cross-fade thins a receding near plant's blades instead of dithering them, so no pass needs a
// discard), bent by `tip` (plant heights) as quadPoint bends a card: by tip * height * fraction^2 sideways, dropping
// so the blade keeps its length.
SWARD_BLADE_FUNCTION vec3 bladePoint(BladeShape s, uint level, uint edge, float widthScale, float height, vec3 up,
                                     vec2 tip) {
    float t = float(level) / float(kBladeSegments);
    float along = s.reach * t;
    float w = s.width * widthScale * (1.0f - t * t);
    vec3 position = s.root + s.rise * along + s.outward * (s.curl * along * t) + s.side * (w * (float(edge) - 0.5f));
    float f = bladeFraction(s, level, height);
    float bend = f * f;
    float drop = height * (1.0f - sqrt(max(1.0f - dot(tip, tip), 0.0f)));
    return position + vec3(tip.x * height, tip.y * height, 0.0f) * bend - up * (drop * bend);
}

#ifdef __cplusplus
} // namespace sward::gpu
#endif
#undef SWARD_CONST
#undef SWARD_BLADE_FUNCTION
#endif
