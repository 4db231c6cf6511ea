// Per-plant shading terms of the colour pass, computed once per vertex instead of once per fragment: on a CPU
// driver every fragment lane runs every instruction (both sides of each branch), and all of this is constant over a
// plant. The fragment shader (plant.frag) adds only what varies across the plant: texel, sun shadow and the darkening
// towards the base. Needs frame.glsl first.
#ifndef SWARD_PLANT_SHADING_GLSL
#define SWARD_PLANT_SHADING_GLSL

struct PlantShading {
    mat3 albedo;       // albedo = albedo * texel.rgb + albedoOffset
    vec3 albedoOffset;
    vec3 sunLight;     // sun radiance times the wrap-lit leaf's response, before the shadow
    vec3 ambient;      // sky ambient for the plant's up, before the darkening towards the base
};

// `fade`: ExpandedPlant::fade (the plant's state in bits 17-20), `up`: the plant's unit up vector.
PlantShading plantShading(uint fade, uint lod, vec3 up, float random) {
    PlantShading s;
    s.albedo = mat3(mix(0.8, 1.15, random)); // per-plant brightness variation
    s.albedoOffset = vec3(0.0);
    uint state = bitfieldExtract(fade, 17, 4);
    // Flattened blades show their paler undersides and bruised, straw-coloured stems: mix 40 % of the texel's
    // luminance, tinted straw, into the texel (a linear map of the texel: 0.6 I + 0.4 straw * luminance^T).
    if (state == kPlantStateFelled)
        s.albedo *= 0.6 * mat3(1.0) + 0.4 * outerProduct(vec3(1.5, 1.35, 0.7), vec3(0.2126, 0.7152, 0.0722));
    // Viewer overlays (sward-view): LOD bands, and the plants the interaction has moved (paper Figure 7).
    if ((frame.debug.x & kDebugLodColors) != 0u) {
        vec3 tint = lod == kLodNear ? vec3(0.9, 0.15, 0.1) : lod == kLodMid ? vec3(0.15, 0.8, 0.1) : vec3(0.15, 0.3, 0.95);
        s.albedo = outerProduct(0.4 * tint, vec3(0.0, 1.0, 0.0)); // tint * (0.6 + 0.4 * texel.g)
        s.albedoOffset = 0.6 * tint;
    }
    if ((frame.debug.x & kDebugUpdatedPlants) != 0u && state != kPlantStateRest) {
        s.albedo = mat3(0.0);
        s.albedoOffset = state == kPlantStateRecovering ? vec3(1.0, 0.55, 0.05)
                       : state == kPlantStateFelled     ? vec3(0.9, 0.05, 0.05)
                                                        : vec3(0.7, 0.1, 0.9);
    }
    // Thin leaves: wrap lighting lets light through from behind.
    s.sunLight = frame.sunRadiance.rgb * clamp(dot(up, frame.sunDirection.xyz) * 0.6 + 0.4, 0.0, 1.0);
    s.ambient = ambientLight(up);
    return s;
}

#endif
