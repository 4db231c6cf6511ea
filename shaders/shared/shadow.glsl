// Cascaded sun shadows (kBindingShadowMap of the shading passes; world/sun_shadow.h fits the cascades): cascade k
// is tile k (FrameConstants::shadowTiles) of a row of square reversed-Z maps, looked up with 4 or 1 hardware-PCF taps.
// A point uses the cascade whose distance shell holds it (distance to the reference camera, so a stereo pair's two
// views agree); over the last kShadowBlend of a shell it dithers into the next cascade and, after the last, fades
// into no shadow: no edge anywhere.
#ifndef SWARD_SHADOW_GLSL
#define SWARD_SHADOW_GLSL

#include "config.h"
#include "gpu_layout.h" // pcgHash

layout(set = 0, binding = kBindingShadowMap) uniform sampler2DShadow shadowMap;

// The map coordinate of a world point in cascade k: x, y the texel in the tile's row of maps, z the compare
// reference (reversed Z: larger is closer to the sun).
vec3 cascadeCoordinate(uint k, vec3 world) {
    vec3 ndc = (frame.shadowCascades[k] * vec4(world, 1.0)).xyz; // orthographic: w = 1
    vec4 tile = frame.shadowTiles[k];
    // The fit holds every receiver inside its map; the clamp keeps the taps off the neighbouring tile regardless.
    vec2 uv = clamp(ndc.xy * 0.5 + 0.5, vec2(tile.w), vec2(1.0 - tile.w));
    return vec3(tile.x + uv.x * tile.y, uv.y * tile.z, ndc.z + frame.shadowBias[k]);
}

// Ground and objects: four hardware-PCF taps (a 4 x 4 texel footprint). Each tap is a bilinear compare of four
// texels, the most expensive thing a fragment does on a CPU driver; plants take one (plantShadow): their own
// noisy alpha hides its harder edge, the smooth ground would not.
float cascadeShadow(uint k, vec3 world) {
    vec3 at = cascadeCoordinate(k, world);
    vec2 tap = 0.5 * frame.shadowTiles[k].w * frame.shadowTiles[k].yz;
    float lit = texture(shadowMap, vec3(at.xy + vec2(-tap.x, -tap.y), at.z));
    lit += texture(shadowMap, vec3(at.xy + vec2(tap.x, -tap.y), at.z));
    lit += texture(shadowMap, vec3(at.xy + vec2(-tap.x, tap.y), at.z));
    lit += texture(shadowMap, vec3(at.xy + vec2(tap.x, tap.y), at.z));
    return lit * 0.25;
}

// The cascade a point at distance `d` from shadowOrigin uses, and how far into no shadow it has faded (after the
// last cascade). `u` in [0, 1) decides the blend band: a point takes the next cascade with probability t.
struct ShadowCascadeChoice {
    uint k;     // cascade; shadowParams.x (the count) when beyond every cascade
    float fade; // 1: no shadow at all, 0: the cascade's shadow
};

ShadowCascadeChoice chooseShadowCascade(float d, float u) {
    uint count = uint(frame.shadowParams.x);
    uint k = 0u;
    while (k < count && d > frame.shadowEnds[k]) ++k;
    if (k == count) return ShadowCascadeChoice(count, 1.0);
    float begin = k == 0u ? 0.0 : frame.shadowEnds[k - 1u];
    float blendFrom = frame.shadowEnds[k] - kShadowBlend * (frame.shadowEnds[k] - begin);
    float t = clamp((d - blendFrom) / (frame.shadowEnds[k] - blendFrom), 0.0, 1.0);
    bool last = k + 1u == count;
    if (!last && t > u) ++k;
    return ShadowCascadeChoice(k, last ? t : 0.0);
}

float sunShadow(vec3 world) {
    // In a blend band a point takes the next cascade with probability t, by a hash of its 1 cm cell (both views of a
    // stereo pair decide alike): one lookup per fragment. A CPU driver runs both sides of a branch, so blending two
    // lookups would cost every fragment twice the taps.
    ivec3 cell = ivec3(floor(world * 100.0));
    float u = unitFromHash(pcgHash(uint(cell.x) + pcgHash(uint(cell.y) + pcgHash(uint(cell.z)))));
    ShadowCascadeChoice choice = chooseShadowCascade(distance(world, frame.shadowOrigin.xyz), u);
    if (choice.fade == 1.0) return 1.0;
    return mix(cascadeShadow(choice.k, world), 1.0, choice.fade);
}

// Plants: one cascade per plant, chosen at its root by a hash of the plant (`u`), so a plant never straddles two
// cascades. The vertex shader computes its vertex's map coordinate (x, y: the tile's texel, z: the compare
// reference); the cascade's projection is affine, so the interpolated coordinate is the projection of the
// interpolated world point and the fragment does one hardware-PCF tap and nothing else (plantShadow). Clamping
// each vertex to the tile keeps every interpolated coordinate inside it (the tile is convex).
vec4 plantShadowCoordinate(vec3 world, vec3 root, float u) {
    ShadowCascadeChoice choice = chooseShadowCascade(distance(root, frame.shadowOrigin.xyz), u);
    if (choice.fade == 1.0) return vec4(0.5, 0.5, 0.0, 1.0); // any coordinate: faded out entirely
    return vec4(cascadeCoordinate(choice.k, world), choice.fade);
}

// `coordinate` from plantShadowCoordinate, interpolated; w is the plant's fade into no shadow (flat over a plant).
float plantShadow(vec4 coordinate) { return mix(texture(shadowMap, coordinate.xyz), 1.0, coordinate.w); }

#endif
