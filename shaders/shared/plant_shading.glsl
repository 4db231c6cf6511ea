// Shading terms of the colour pass computed per vertex instead of per fragment: on a CPU driver every fragment lane
// runs every instruction (both sides of each branch). The per-plant terms (albedo, ambient) are constant over a
// plant; the sun's terms vary smoothly across a card (its rounded normal) and are interpolated from its corners.
// The fragment shader (plant.frag) adds only what varies faster: texel, sun shadow and the occlusion towards the
// base. Needs frame.glsl first.
#ifndef SWARD_PLANT_SHADING_GLSL
#define SWARD_PLANT_SHADING_GLSL

#include "plant_layout.h" // the plant states

struct PlantShading {
    mat3 albedo;       // albedo = albedo * texel.rgb + albedoOffset
    vec3 albedoOffset;
    vec3 ambient;      // sky ambient for the plant's up, before the occlusion towards the base
};

// Rotation of an RGB colour about the grey axis by `angle` radians (Rodrigues): a hue shift that keeps grey grey.
mat3 hueRotation(float angle) {
    float c = cos(angle), s = sin(angle) * 0.57735027, k = (1.0 - c) / 3.0;
    // Columns of c I + k (1 1 1)(1 1 1)^T + s [(1 1 1)]x.
    return mat3(c + k, k + s, k - s, k - s, c + k, k + s, k + s, k - s, c + k);
}

// `fade`: ExpandedPlant::fade (the plant's state in bits 17-20), `up`: the plant's unit up vector, `random`: the
// plant's random value, `colourHash`: plantColourHash of the plant.
PlantShading plantShading(uint fade, uint lod, vec3 up, float random, float colourHash) {
    PlantShading s;
    // Per-plant variation: value +-15 % from the plant's random value, and hue +-10 degrees from its own hash
    // (negative: green towards yellow, positive: towards blue-green), as neighbouring real plants differ.
    s.albedo = mix(0.85, 1.15, random) * hueRotation(radians(20.0) * (colourHash - 0.5));
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
    s.ambient = ambientLight(up);
    return s;
}

// The sun's light at a corner, before the shadow: `colour` * terms.x reflected and transmitted by the leaf (times the
// albedo), frame.sunRadiance * terms.y the leaf's specular sheen (added without it). The fragment shaders take the
// colour flat (which side of the leaf the sun lights changes at most once across a card) and interpolate only the
// two scalars: on lavapipe each interpolated component costs every fragment lane, and six of them cost the meadow's
// main pass about 1.1x.
struct PlantSunLight {
    vec3 colour; // the sun's radiance, tinted when it is transmitted through the leaf
    vec2 terms;  // x: the irradiance factor of the rounded normal, y: the sheen
};

// The sun's diffuse light and sheen of a fragment from its PlantSunLight's flat colour and interpolated terms.
vec3 plantSunDiffuse(vec3 colour, vec2 terms) { return colour * terms.x; }
vec3 plantSunSheen(vec2 terms) { return frame.sunRadiance.rgb * terms.y; }

// Sun light at one corner of a card (or blade): `face` is its unit normal (either side), `side` its unit horizontal
// direction, `across` the corner's place across the plant along `side` (-1 .. 1, 0 on the plant's axis), `up` the
// plant's up, `toCamera` the unit direction from the corner to the camera.
// A tuft is lit as one rounded body, not as flat cards: its shading normal leans outwards from the axis (the side of
// the tuft facing the sun is lit, the other darker, smoothly) and is the same for every card through a point, so
// crossing cards do not flicker against each other. A thin leaf reflects the sun that reaches its camera side and
// transmits the sun that reaches its back, a little less and yellow-green (the card's face only picks which); a
// small broad specular lobe gives the waxy sheen. The wrap stands for the light a tuft scatters inside.
PlantSunLight plantSunLight(vec3 face, vec3 side, float across, vec3 up, vec3 toCamera) {
    const float kRounding = 0.4; // the normal's outward lean at the plant's edge, against 1 up
    vec3 n = normalize(up + side * (kRounding * across));
    vec3 l = frame.sunDirection.xyz;
    float d = dot(n, l);
    const float kWrap = 0.5;
    // Scaled so a plant standing upright under a sun 40 degrees high gets about the light of the wrap lighting
    // before (0.8 of the sun's radiance): the plant's average brightness stays.
    float irradiance = 1.05 * clamp((d + kWrap) / (1.0 + kWrap), 0.0, 1.0);
    const vec3 kTransmittance = vec3(0.9, 0.9, 0.65); // relative to the albedo: leaves pass more yellow-green light
    bool backlit = dot(face, l) * dot(face, toCamera) < 0.0;
    PlantSunLight s;
    s.colour = frame.sunRadiance.rgb * (backlit ? kTransmittance : vec3(1.0));
    float specular = max(dot(n, normalize(l + toCamera)), 0.0);
    specular *= specular;
    specular *= specular;
    s.terms = vec2(irradiance, 0.03 * specular * specular * max(d, 0.0));
    return s;
}

#endif
