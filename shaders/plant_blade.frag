#version 460
#extension GL_GOOGLE_include_directive : require
// Blade shading, main pass (plant_blade.vert): opaque, no discard and no alpha to coverage, so the depth test runs
// before this shader and a pixel behind the nearest blade costs no shading. As plant.frag: the sun reflected and
// transmitted with a sheen, its shadow, sky ambient, occlusion towards the tuft's base; the blade is darker at its
// base and lighter towards its tip.
#include "shared/frame.glsl"
#include "shared/shadow.glsl"
#include "shared/plant_shading.glsl"

layout(location = 2) in float inHeightFraction;
layout(location = 3) in float inAlong;
layout(location = 4) in vec4 inShadow;
layout(location = 5) flat in vec3 inAlbedo;
layout(location = 6) in vec2 inSunTerms;
layout(location = 7) flat in vec3 inAmbient;
layout(location = 8) flat in vec3 inSunColour;
layout(location = 12) in vec4 inHaze;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 albedo = inAlbedo * mix(0.8, 1.0, inAlong);
    // plant.frag's occlusion towards the base: the cube of the depth below the plant's top.
    float depth = clamp(1.0 - inHeightFraction, 0.0, 1.0);
    depth *= depth * depth;
    float sun = plantShadow(inShadow) * (1.0 - 0.45 * depth);
    vec3 light = plantSunDiffuse(inSunColour, inSunTerms) * sun + inAmbient * (1.0 - 0.65 * depth);
    outColor = vec4(albedo * light + plantSunSheen(inSunTerms) * sun, 1.0);
    outColor.rgb = applyHaze(outColor.rgb, inHaze);
}
