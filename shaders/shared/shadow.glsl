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

// `taps` 4 (ground, objects: a 4 x 4 texel footprint) or 1 (plants: 2 x 2 texels). Each tap is a bilinear
// compare of four texels, the most expensive thing a fragment does on a CPU driver; a plant's own noisy alpha hides
// the harder edge of one tap, the smooth ground would not.
float cascadeShadow(uint k, vec3 world, uint taps) {
    vec3 ndc = (frame.shadowCascades[k] * vec4(world, 1.0)).xyz; // orthographic: w = 1
    vec4 tile = frame.shadowTiles[k];
    // The fit holds every receiver inside its map; the clamp keeps the taps off the neighbouring tile regardless.
    vec2 uv = clamp(ndc.xy * 0.5 + 0.5, vec2(tile.w), vec2(1.0 - tile.w));
    uv = vec2(tile.x + uv.x * tile.y, uv.y * tile.z);
    float reference = ndc.z + frame.shadowBias[k]; // reversed Z: larger is closer to the sun
    if (taps == 1u) return texture(shadowMap, vec3(uv, reference));
    vec2 tap = 0.5 * tile.w * tile.yz;
    float lit = texture(shadowMap, vec3(uv + vec2(-tap.x, -tap.y), reference));
    lit += texture(shadowMap, vec3(uv + vec2(tap.x, -tap.y), reference));
    lit += texture(shadowMap, vec3(uv + vec2(-tap.x, tap.y), reference));
    lit += texture(shadowMap, vec3(uv + vec2(tap.x, tap.y), reference));
    return lit * 0.25;
}

float sunShadow(vec3 world, uint taps) {
    uint count = uint(frame.shadowParams.x);
    float d = distance(world, frame.shadowOrigin.xyz);
    uint k = 0u;
    while (k < count && d > frame.shadowEnds[k]) ++k;
    if (k == count) return 1.0;
    float begin = k == 0u ? 0.0 : frame.shadowEnds[k - 1u];
    float blendFrom = frame.shadowEnds[k] - kShadowBlend * (frame.shadowEnds[k] - begin);
    float t = clamp((d - blendFrom) / (frame.shadowEnds[k] - blendFrom), 0.0, 1.0);
    bool last = k + 1u == count;
    // In a blend band a point takes the next cascade with probability t, by a hash of its 1 cm cell (both views of a
    // stereo pair decide alike): one lookup per fragment. A CPU driver runs both sides of a branch, so blending two
    // lookups would cost every fragment twice the taps.
    ivec3 cell = ivec3(floor(world * 100.0));
    if (!last && t > unitFromHash(pcgHash(uint(cell.x) + pcgHash(uint(cell.y) + pcgHash(uint(cell.z)))))) ++k;
    float lit = cascadeShadow(k, world, taps);
    return last ? mix(lit, 1.0, t) : lit;
}

#endif
