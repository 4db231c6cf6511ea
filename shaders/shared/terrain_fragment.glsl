#ifndef SWARD_TERRAIN_FRAGMENT_GLSL
#define SWARD_TERRAIN_FRAGMENT_GLSL
// Terrain shading: a mesh ground's material colour and texture, or soil albedo varied by slope, sun (Lambert) +
// hemispherical ambient. Under dense vegetation the ground is turf (gpu_layout.h, turfFraction): the sward's low
// base, coloured from the cover map (vegetation/cover_map.h), so the meadow is closed seen from above. Beyond the
// far LOD limit, where the plants have dissolved, the ground takes the vegetation's look from the cover map, lit
// as the plants are, so the meadow goes on in colour instead of ending in a bare band. Ruts (track.vert) are
// compacted, darker soil (turf is pressed, not removed: the felled plants over it show the track there);
// terrain_holes.frag leaves their blocks to them.
#include "shared/frame.glsl"
#include "shared/ground_cover.glsl"
#ifdef SWARD_TERRAIN_HOLES
#include "shared/ground_tracks.glsl"
#endif
#include "shared/shadow.glsl"

layout(set = 0, binding = kBindingGroundTextures) uniform sampler2DArray groundTextures;

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inViewDepth;
layout(location = 3) in vec4 inAlbedo;
layout(location = 4) in vec3 inUvLayer; // flat in practice: the layer is constant per triangle
layout(location = 6) in float inRut;    // metres pressed down (render/track_renderer.h)

layout(location = 0) out vec4 outColor;

// Mean of plant.frag's per-plant brightness factor mix(0.8, 1.15, random), and the mean ambient occlusion of the
// plant parts seen from afar (plant.frag's mix(0.35, 1.0, height fraction); calibrated with kCoverDepth below).
const float kPlantBrightness = 0.975;
const float kPlantOcclusion = 0.77;
// Seen at elevation angle e, plants showing S m^2 of side area per m^2 of ground hide the fraction
// 1 - exp(-S / (kCoverDepth * tan e)) of it (a ray crossing a random layer of leaves): all of it at grazing angles,
// less from above. Calibrated on the default meadow (FarCoverTest: strips across lod.far from 4, 12 and 30 m up).
const float kCoverDepth = 1.1;
// Mean sunlit fraction of the plant surface seen from afar: the plants shade each other and the ground between them.
const float kPlantSunlit = 0.95;
// Turf: the sward's base is darker than the plants' mean (older leaves, litter, shade of the blades above).
const float kTurfShade = 0.55;
// A rut: soil compacted by the wheel is darker (smoother, wetter); fully so from this depth on.
const float kRutFullDepth = 0.01;
const float kRutDarkening = 0.4;

// Fraction of the ground the far cover hides at `world`, seen from the camera.
float hiddenFraction(float area, vec3 world) {
    vec3 toCamera = frame.cameraPosition.xyz - world;
    float tanElevation = max(toCamera.z, 0.0) / max(length(toCamera.xy), 1e-3);
    return 1.0 - exp(-area / max(kCoverDepth * tanElevation, 1e-6));
}

// How much of the pixel the far cover takes: 0 inside the plants' range, rising over their dissolve band exactly
// as their dither removes them (plants use the same 3D distance to the camera).
float coverWeight(vec3 world) {
    float start = frame.coverBand.x - 0.5 * frame.coverBand.y;
    return clamp((distance(world, frame.cameraPosition.xyz) - start) / max(frame.coverBand.y, 1e-3), 0.0, 1.0);
}

// Value noise in [0, 1] on a lattice of `cell` metres: integer hashing (no sin), the same on every device.
float latticeNoise(vec2 xy, float cell) {
    vec2 p = xy / cell, i = floor(p), f = p - i;
    uvec2 c = uvec2(ivec2(i));
    float n00 = unitFromHash(pcgHash(c.x + pcgHash(c.y)));
    float n10 = unitFromHash(pcgHash(c.x + 1u + pcgHash(c.y)));
    float n01 = unitFromHash(pcgHash(c.x + pcgHash(c.y + 1u)));
    float n11 = unitFromHash(pcgHash(c.x + 1u + pcgHash(c.y + 1u)));
    f = f * f * (3.0 - 2.0 * f);
    return mix(mix(n00, n10, f.x), mix(n01, n11, f.x), f.y);
}

// Brightness of the turf around `world`: clumps of a few decimetres and short shoots of a few centimetres; the
// fine octave fades where a pixel covers more than it (no shimmer in the distance).
float turfGrain(vec3 world) {
    float footprint = length(fwidth(world.xy));
    float fine = mix(latticeNoise(world.xy, 0.035), 0.5, clamp(footprint / 0.035 - 0.5, 0.0, 1.0));
    return 0.65 + 0.45 * latticeNoise(world.xy, 0.3) + 0.35 * (fine - 0.5);
}

// plant.frag's light for a plant standing along the ground normal (up_normal_blend aside).
vec3 plantLight(vec3 n, float shadow) {
    float sun = clamp(dot(n, frame.sunDirection.xyz) * 0.6 + 0.4, 0.0, 1.0) * shadow * kPlantSunlit;
    return frame.sunRadiance.rgb * sun + ambientLight(n) * kPlantOcclusion;
}

void main() {
#ifdef SWARD_TERRAIN_HOLES
    if (inTrackPatch(inWorld.xy)) discard;
#endif
    vec3 n = normalize(inNormal);
    float pressed = clamp(inRut / kRutFullDepth, 0.0, 1.0);
    float slope = 1.0 - n.z;
    vec3 soil = vec3(0.16, 0.12, 0.07);
    vec3 compact = vec3(0.07, 0.10, 0.03);
    // Low-frequency variation from position only (no texture): keeps large flat areas from looking uniform.
    float variation = 0.5 + 0.5 * sin(inWorld.x * 0.071 + 1.3 * sin(inWorld.y * 0.053));
    vec3 albedo = mix(compact, soil, clamp(slope * 4.0 + 0.25 * variation, 0.0, 1.0));
    // A mesh ground is drawn with its materials' base colours, times their textures.
    if (inAlbedo.a > 0.0) albedo = inAlbedo.rgb;
    if (inUvLayer.z >= 0.0) albedo *= texture(groundTextures, vec3(inUvLayer.xy, round(inUvLayer.z))).rgb;
    albedo *= 1.0 - kRutDarkening * pressed;
    float shadow = sunShadow(inWorld);
    float sun = max(dot(n, frame.sunDirection.xyz), 0.0) * shadow;
    vec3 color = albedo * (frame.sunRadiance.rgb * sun + ambientLight(n));
    vec2 uv = coverUv(inWorld);
    vec4 cover = groundCover(uv);
    float turf = turfFraction(cover.a);
    if (turf > 0.0) color = mix(color, cover.rgb * (kTurfShade * turfGrain(inWorld)) * plantLight(n, shadow), turf);
    float weight = inCoverTile(uv) ? coverWeight(inWorld) : 0.0;
    if (weight > 0.0)
        color = mix(color, cover.rgb * kPlantBrightness * plantLight(n, shadow), weight * hiddenFraction(cover.a, inWorld));
    outColor = vec4(color, 1.0);
}

#endif
