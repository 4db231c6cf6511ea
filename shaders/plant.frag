#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shading, main pass. With 4x MSAA the atlas alpha drives alpha-to-coverage (sharpened to about one
// texel of transition, so edges stay crisp but anti-aliased); at 1x it is an alpha test at 0.5.
// Lighting uses the plant's up vector (paper 3.4), sun with shadow, sky ambient, darker towards the base; the
// per-plant terms and the sun shadow's map coordinate come from the vertex shader (shared/plant_shading.glsl,
// plantShadowCoordinate).
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"
#include "shared/shadow.glsl"

layout(constant_id = 1) const bool ALPHA_TO_COVERAGE = false;
layout(location = 3) in vec4 inShadow; // plantShadowCoordinate, from the vertex shader
layout(location = 10) flat in mat3 inAlbedo; // locations 10-12
layout(location = 13) flat in vec3 inAlbedoOffset;
layout(location = 14) flat in vec3 inSunLight;
layout(location = 15) flat in vec3 inAmbient;
layout(location = 0) out vec4 outColor;

void main() {
    vec4 texel = plantTexel(); // before any discard: its mip level needs the whole 2x2 quad
    if (!keepFragment()) discard;
    float alpha = texel.a;
    if (ALPHA_TO_COVERAGE) {
        alpha = (alpha - 0.5) / max(fwidth(alpha), 1e-4) + 0.5;
        if (alpha <= 0.0) discard;
    } else if (alpha < 0.5) {
        discard;
    }
    // Per-plant terms from the vertex shader (plant_shading.glsl); here only what varies across the plant.
    vec3 albedo = inAlbedo * texel.rgb + inAlbedoOffset;
    float occlusion = mix(0.35, 1.0, inHeightFraction); // ambient occlusion darkens the base
    vec3 light = inSunLight * plantShadow(inShadow) + inAmbient * occlusion;
    outColor = vec4(albedo * light, clamp(alpha, 0.0, 1.0));
}
