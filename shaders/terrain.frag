#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain shading: a mesh ground's material colour and texture, or soil / dry-grass albedo varied by slope and height, sun
// (Lambert) + hemispherical ambient. Beyond the far LOD limit, where the plants have dissolved, the ground takes
// the vegetation's look from the cover map (vegetation/cover_map.h), lit as the plants are, so the meadow goes on
// in colour instead of ending in a bare band.
#include "shared/frame.glsl"
#include "shared/shadow.glsl"

layout(set = 0, binding = kBindingCoverMap) uniform sampler2D coverMap;
layout(set = 0, binding = kBindingGroundTextures) uniform sampler2DArray groundTextures;
layout(push_constant) uniform Push { TerrainTileConstants tile; };

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inViewDepth;
layout(location = 3) in vec4 inAlbedo;
layout(location = 4) in vec3 inUvLayer; // flat in practice: the layer is constant per triangle

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

// Fraction of the ground the far cover hides at `world`, seen from the camera.
float hiddenFraction(float area, vec3 world) {
    vec3 toCamera = frame.cameraPosition.xyz - world;
    float tanElevation = max(toCamera.z, 0.0) / max(length(toCamera.xy), 1e-3);
    return 1.0 - exp(-area / max(kCoverDepth * tanElevation, 1e-6));
}

// How much of the pixel the far cover takes: 0 inside the plants' range, rising over their dissolve band exactly
// as their dither removes them (plants use the same 3D distance to the camera). uv: `world` in the cover's tile.
float coverWeight(vec3 world, vec2 uv) {
    if (tile.coverRect.z == 0.0) return 0.0;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 0.0;
    float start = frame.coverBand.x - 0.5 * frame.coverBand.y;
    return clamp((distance(world, frame.cameraPosition.xyz) - start) / max(frame.coverBand.y, 1e-3), 0.0, 1.0);
}

void main() {
    vec3 n = normalize(inNormal);
    float slope = 1.0 - n.z;
    // Dark turf: under the vegetation the ground reads as the dense base of the sward, not as bare soil.
    vec3 soil = vec3(0.16, 0.12, 0.07);
    vec3 turf = vec3(0.07, 0.10, 0.03);
    // Low-frequency variation from position only (no texture): keeps large flat areas from looking uniform.
    float variation = 0.5 + 0.5 * sin(inWorld.x * 0.071 + 1.3 * sin(inWorld.y * 0.053));
    vec3 albedo = mix(turf, soil, clamp(slope * 4.0 + 0.25 * variation, 0.0, 1.0));
    // A mesh ground is drawn with its materials' base colours, times their textures.
    if (inAlbedo.a > 0.0) albedo = inAlbedo.rgb;
    if (inUvLayer.z >= 0.0) albedo *= texture(groundTextures, vec3(inUvLayer.xy, round(inUvLayer.z))).rgb;
    float shadow = sunShadow(inWorld);
    float sun = max(dot(n, frame.sunDirection.xyz), 0.0) * shadow;
    vec3 color = albedo * (frame.sunRadiance.rgb * sun + ambientLight(n));
    vec2 uv = (inWorld.xy - tile.coverRect.xy) * tile.coverRect.z;
    float weight = coverWeight(inWorld, uv);
    if (weight > 0.0) {
        // The texture's v runs north to south (top row north), as the grass map's.
        vec4 cover = texture(coverMap, vec2(uv.x, 1.0 - uv.y));
        // plant.frag's light for a plant standing along the ground normal (up_normal_blend aside).
        float plantSun = clamp(dot(n, frame.sunDirection.xyz) * 0.6 + 0.4, 0.0, 1.0) * shadow * kPlantSunlit;
        vec3 plantLight = frame.sunRadiance.rgb * plantSun + ambientLight(n) * kPlantOcclusion;
        color = mix(color, cover.rgb * kPlantBrightness * plantLight, weight * hiddenFraction(cover.a, inWorld));
    }
    outColor = vec4(color, 1.0);
}
