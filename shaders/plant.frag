#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shading, main pass. With 4x MSAA the atlas alpha drives alpha-to-coverage (sharpened to about one
// texel of transition, so edges stay crisp but anti-aliased); at 1x it is an alpha test at 0.5.
// Lighting uses the plant's up vector (paper 3.4), sun with shadow, sky ambient, darker towards the base.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"
#include "shared/shadow.glsl"
#include "shared/plant_layout.h"

layout(constant_id = 1) const bool ALPHA_TO_COVERAGE = false;
layout(location = 0) out vec4 outColor;

void main() {
    if (!keepFragment()) discard;
    vec4 texel = texture(atlas, inUv);
    float alpha = texel.a;
    if (ALPHA_TO_COVERAGE) {
        alpha = (alpha - 0.5) / max(fwidth(alpha), 1e-4) + 0.5;
        if (alpha <= 0.0) discard;
    } else if (alpha < 0.5) {
        discard;
    }
    vec3 up = normalize(inUp);
    vec3 albedo = texel.rgb * mix(0.8, 1.15, inRandom);
    uint state = bitfieldExtract(inFade, 17, 4);
    // Flattened blades show their paler undersides and bruised, straw-coloured stems.
    if (state == kPlantStateFelled) albedo = mix(albedo, dot(albedo, vec3(0.2126, 0.7152, 0.0722)) * vec3(1.5, 1.35, 0.7), 0.4);
    // Viewer overlays (sward-view): LOD bands, and the plants the interaction has moved (paper Figure 7).
    if ((frame.debug.x & kDebugLodColors) != 0u) {
        uint lod = bitfieldExtract(inFade, 21, 2); // set by plant.vert
        albedo = (lod == kLodNear ? vec3(0.9, 0.15, 0.1) : lod == kLodMid ? vec3(0.15, 0.8, 0.1) : vec3(0.15, 0.3, 0.95)) *
                 (0.6 + 0.4 * texel.g);
    }
    if ((frame.debug.x & kDebugUpdatedPlants) != 0u && state != kPlantStateRest)
        albedo = state == kPlantStateRecovering ? vec3(1.0, 0.55, 0.05) : state == kPlantStateFelled ? vec3(0.9, 0.05, 0.05)
                                                                                                    : vec3(0.7, 0.1, 0.9);
    // Thin leaves: wrap lighting lets light through from behind, ambient occlusion darkens the base.
    float sun = clamp(dot(up, frame.sunDirection.xyz) * 0.6 + 0.4, 0.0, 1.0) * sunShadow(inWorld);
    float occlusion = mix(0.35, 1.0, inHeightFraction);
    vec3 light = frame.sunRadiance.rgb * sun + ambientLight(up) * occlusion;
    outColor = vec4(albedo * light, clamp(alpha, 0.0, 1.0));
}
