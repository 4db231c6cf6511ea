// Fragment-side plant helpers: atlas alpha and the LOD cross-fade dither shared by colour, truth and shadow.
#ifndef SWARD_PLANT_FRAGMENT_GLSL
#define SWARD_PLANT_FRAGMENT_GLSL

#include "config.h"

layout(set = 0, binding = kBindingAtlas) uniform sampler2D atlas;

layout(location = 0) in vec2 inUv;
layout(location = 2) in float inViewDepth;
layout(location = 4) flat in uint inFade;
layout(location = 5) in float inHeightFraction;
layout(location = 6) flat in float inRandom;
layout(location = 7) flat in uint inLabel; // ground truth only
layout(location = 18) flat in vec4 inUvRect; // the cell's atlas rectangle: u0, v0, u1, v1
layout(location = 19) flat in vec2 inMerge; // far merging: x PlantQuad::repeat, y PlantQuad::opacity

// The atlas coordinate of this fragment. inUv is in cell coordinates; on a far billboard merged in width
// (inMerge.x > 1) u runs over 0..inMerge.x and shows that many copies of the plant side by side, every other one
// mirrored so each seam is continuous: plants at their own width, not one plant stretched.
vec2 plantAtlasUv() {
    float u = inUv.x;
    if (inMerge.x > 1.0) {
        float copy = floor(u);
        u -= copy;
        if (mod(copy, 2.0) == 1.0) u = 1.0 - u;
    }
    return inUvRect.xy + (inUvRect.zw - inUvRect.xy) * vec2(u, inUv.y);
}

// A far billboard merged in depth stands for several cards at its place (depthMergeScale in gpu_layout.h). Alpha is
// kept below 1 so that an opaque texel, too, fades out with the exponent: none pops.
float mergedAlpha(float alpha) {
    return inMerge.y != 1.0 ? 1.0 - pow(1.0 - min(alpha, 0.996), inMerge.y) : alpha;
}

// The plant's atlas texel here, filtered trilinearly. The mip level comes from the unwrapped coordinate, the same on
// both sides of a merged billboard's seam. The colour and truth passes both sample through here, so they keep the
// same texels.
vec4 plantTexel() {
    vec2 size = inUvRect.zw - inUvRect.xy;
    vec4 texel = textureGrad(atlas, plantAtlasUv(), dFdx(inUv) * size, dFdy(inUv) * size);
    texel.a = mergedAlpha(texel.a);
    return texel;
}

// A far billboard's colour is prefiltered over this many times its footprint (a mip level and a half coarser): a
// plant a few pixels high shows its mean colour, as a camera's optics and demosaicing would, not a texel-sharp
// pattern of blades. Its alpha, and so its silhouette and the truth pass's coverage, stays at the footprint
// (plantTexel): one coarser fetch for both thinned the far field at 1x, where its averaged alpha fails the test.
const float kFarColourFootprint = 2.8;

// The colour pass's albedo texel: plantTexel's colour, or for a far billboard the colour over kFarColourFootprint.
// plant.frag calls it only in pipelines that may draw far billboards (FAR_BILLBOARDS). A loop of 0 or 1 trips, not an
// if: on lavapipe every lane runs both sides of a branch, but a loop whose count is 0 for every lane (bits 21-22 of
// inFade: the LOD, plant.vert) ends at once, so in a draw of mixed LODs (the baked plants) only far lanes pay.
vec3 plantColourTexel(vec3 colour) {
    vec2 size = (inUvRect.zw - inUvRect.xy) * kFarColourFootprint;
    vec2 dx = dFdx(inUv) * size, dy = dFdy(inUv) * size;
    uint fetches = ((inFade >> 21) & 3u) == kLodFar ? 1u : 0u;
    for (uint i = 0u; i < fetches; ++i) colour = textureGrad(atlas, plantAtlasUv(), dx, dy).rgb;
    return colour;
}

// The shadow pass's alpha: the nearest texel of atlas level `level`, one level for the whole draw. lavapipe's sampler
// is fast only when every lane of a SIMD vector reads one level: with one, the shadow pass takes about 0.8 of its
// time with a level per fragment (docs/benchmarks.md, "fourteenth part"). The fetch stays inside the plant's cell.
float plantShadowAlpha(int level) {
    vec2 size = vec2(textureSize(atlas, level));
    ivec2 texel = min(ivec2(plantAtlasUv() * size), ivec2(inUvRect.zw * size) - 1);
    return mergedAlpha(texelFetch(atlas, texel, level).a);
}

// Cross-fade between two LOD copies of one plant: both copies compute the same threshold per pixel, the lower
// copy keeps the pixel when threshold >= t, the upper copy when threshold < t: exactly one survives.
bool keepFragment() {
    float t = float(inFade & 0xffu) * (1.0 / 255.0);
    if (t == 0.0 && (inFade & 0x10000u) == 0u) return true;
    // Interleaved gradient noise (Jimenez 2014), shifted per plant so neighbours do not dissolve in lockstep.
    vec2 p = gl_FragCoord.xy + vec2(inRandom * 97.0, inRandom * 61.0);
    float threshold = fract(52.9829189 * fract(dot(p, vec2(0.06711056, 0.00583715))));
    return (inFade & 0x10000u) != 0u ? threshold < t : threshold >= t;
}

#endif
