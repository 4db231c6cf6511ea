#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shading, main pass. With 4x MSAA the atlas alpha drives alpha-to-coverage (sharpened to about two pixels
// of transition, so edges stay crisp but anti-aliased); at 1x it is an alpha test at 0.5.
// Lighting: the sun reflected and transmitted through the leaf with a sheen, on a shading normal rounded across the
// plant, with the shadow; sky ambient for the plant's up vector (paper 3.4); occlusion towards the base; the haze.
// The per-plant and per-corner terms, the sun shadow's map coordinate and the haze come from the vertex shader
// (shared/plant_shading.glsl, plantShadowCoordinate, hazeAt): each fragment lane runs only what varies faster.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"
#include "shared/shadow.glsl"
#include "shared/plant_shading.glsl"

layout(constant_id = 1) const bool ALPHA_TO_COVERAGE = false;
// Whether this pipeline's draws may hold far billboards (VegetationRenderer: the far LOD's draw and the baked plants;
// not the near and mid draws). On lavapipe every lane runs every instruction, so the far billboards' second fetch and
// pixel-centre test are compiled out of the near and mid pipeline: they cost the meadow's main pass 1.3x when every
// plant ran them (docs/benchmarks.md, "Issue 47's frame cost").
layout(constant_id = 2) const bool FAR_BILLBOARDS = true;
layout(location = 3) in vec4 inShadow; // plantShadowCoordinate, from the vertex shader
layout(location = 10) flat in mat3 inAlbedo; // locations 10-12
layout(location = 13) flat in vec3 inAlbedoOffset;
layout(location = 14) in vec2 inSunTerms; // plantSunLight, interpolated across the card
layout(location = 15) flat in vec3 inAmbient;
layout(location = 20) flat in vec3 inSunColour; // plantSunLight
layout(location = 21) in vec4 inHaze;     // hazeAt, per vertex
layout(location = 0) out vec4 outColor;

// Whether the pixel centre lies on the card. With MSAA a pixel runs the shader when any of its samples is covered, but
// inputs are interpolated at the centre (extrapolated off the card), where the truth pass samples, and only when it
// covers the centre. A merged far billboard's u runs over 0..inMerge.x.
bool centreOnCard() {
    return inUv.x >= 0.0 && inUv.x <= max(inMerge.x, 1.0) && inUv.y >= 0.0 && inUv.y <= 1.0;
}

void main() {
    vec4 texel = plantTexel(); // before any discard: its mip level needs the whole 2x2 quad
    if (FAR_BILLBOARDS) texel.rgb = plantColourTexel(texel.rgb); // the colour prefiltered (truth keeps the alpha)
    if (!keepFragment()) discard;
    float alpha = texel.a;
    if (ALPHA_TO_COVERAGE) {
        // Near and mid plants over about two pixels: a camera's optics, not a razor edge (the meadow's ground view:
        // sharp texture 0.91 -> 0.88 of the vegetation, Laplacian level 0 0.129 -> 0.116; truth keeps the alpha
        // test at 0.5). Far billboards over one pixel, and only where the truth pass keeps the pixel: alpha >= 0.5
        // at a pixel centre on the card. Against the sky their transition outside the truth's silhouette, and the
        // card's top edge (where a coarse level's filter reaches the cell above, another plant's opaque stems),
        // tinted pixels labelled sky above the horizon (meadow 640x480 4x: 199 -> 1 of the 3,200 sky pixels 2-6 px
        // above it tinted by more than 8 of 255; tools/horizon-colour.py).
        bool far = FAR_BILLBOARDS && ((inFade >> 21) & 3u) == kLodFar;
        if (far && !centreOnCard()) discard;
        float edge = far ? 1.0 : 2.0, offset = far ? 0.0 : 0.5;
        alpha = (alpha - 0.5) / max(edge * fwidth(alpha), 1e-4) + offset;
        if (alpha <= 0.0) discard;
    } else if (alpha < 0.5) {
        discard;
    }
    // Per-plant terms from the vertex shader (plant_shading.glsl); here only what varies across the plant.
    vec3 albedo = inAlbedo * texel.rgb + inAlbedoOffset;
    // Occlusion towards the base: the blades above a point hide the sky and the sun from it, and a tuft's blades
    // crowd together low down, so it grows with the cube of the depth below the top: the lower third is dark (sky
    // 0.3, sun 0.7 at the base), the upper half nearly open. The sun's part adds to its shadow map, which is too
    // coarse for a tuft's own blades. The blades that cast the sun shadow are thin leaves too: near the top, where one
    // or two of them shade a point, 0.3 of the sun comes through; deep in the canopy, through many, none.
    float depth = clamp(1.0 - inHeightFraction, 0.0, 1.0);
    depth *= depth * depth;
    float shadow = plantShadow(inShadow);
    float sun = (shadow + (1.0 - shadow) * 0.3 * (1.0 - depth)) * (1.0 - 0.3 * depth);
    vec3 light = plantSunDiffuse(inSunColour, inSunTerms) * sun + inAmbient * (1.0 - 0.7 * depth);
    outColor = vec4(albedo * light + plantSunSheen(inSunTerms) * sun, clamp(alpha, 0.0, 1.0));
    outColor.rgb = applyHaze(outColor.rgb, inHaze);
}
