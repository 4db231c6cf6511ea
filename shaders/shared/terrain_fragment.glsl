#ifndef SWARD_TERRAIN_FRAGMENT_GLSL
#define SWARD_TERRAIN_FRAGMENT_GLSL
// Terrain shading: a mesh ground's material colour and texture, or a ground material (ground_material.glsl: soil
// with clods, grains, cracks and specks, its relief tilting the shading normal), sun (Lambert) + hemispherical
// ambient. Under dense vegetation the ground is turf (ground_cover.glsl, turfAt): the sward's low base of thatch,
// coloured from the cover map (vegetation/cover_map.h), so the meadow is closed seen from above. Beyond the
// far LOD limit, where the plants have dissolved, the ground takes the vegetation's look from the cover map, lit
// as the plants are, so the meadow goes on in colour instead of ending in a bare band. Ruts (track.vert) are
// compacted, darker soil (turf is pressed, not removed: the felled plants over it show the track there);
// terrain_holes.frag leaves their blocks to them.
#include "shared/frame.glsl"
#include "shared/ground_cover.glsl"
#include "shared/ground_material.glsl"
#include "shared/horizon_ring.glsl"
#ifdef SWARD_TERRAIN_HOLES
#include "shared/ground_tracks.glsl"
#endif
#include "shared/shadow.glsl"

layout(set = 0, binding = kBindingGroundTextures) uniform sampler2DArray groundTextures;
// Per cover texel, each category's grass-map value: how much of its ground_material the bare ground takes.
layout(set = 0, binding = kBindingGroundMaterials) uniform sampler2D groundMaterialWeights;

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inViewDepth;
layout(location = 3) in vec4 inAlbedo;
layout(location = 4) in vec3 inUvLayer; // flat in practice: the layer is constant per triangle
layout(location = 6) in float inRut;    // metres pressed down (render/track_renderer.h)
layout(location = 7) in float inLoose;  // 0..1: soil pushed up beside a rut (track.vert)

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
// A rut: soil compacted by the wheel is darker (smoother, wetter); fully so from this depth on.
const float kRutFullDepth = 0.01;
const float kRutDarkening = 0.4;

// Fraction of the ground the far cover hides at `world`, seen from the camera.
float hiddenFraction(float area, vec3 world) {
    vec3 toCamera = frame.cameraPosition.xyz - world;
    float tanElevation = max(toCamera.z, 0.0) / max(length(toCamera.xy), 1e-3);
    return 1.0 - exp(-area / max(kCoverDepth * tanElevation, 1e-6));
}

// Between the mid LOD limit and the far limit the far billboards stand for the plants but not for the blades between
// them, each far below a pixel there, which a real meadow's far field is full of: the ground between the billboards
// takes this much of the far cover's look at the far limit, rising from none at the mid limit, so the far field's
// gaps do not show bare ground at pixel contrast.
const float kSubpixelCanopy = 0.7;

// How much of the pixel the far cover takes: kSubpixelCanopy at most inside the plants' range, rising to all over
// their dissolve band exactly as their dither removes them (plants use the same 3D distance to the camera).
float coverWeight(vec3 world) {
    float start = frame.coverBand.x - 0.5 * frame.coverBand.y, d = distance(world, frame.cameraPosition.xyz);
    float beyond = clamp((d - start) / max(frame.coverBand.y, 1e-3), 0.0, 1.0);
    float within = clamp((d - frame.coverBand.z) / max(start - frame.coverBand.z, 1e-3), 0.0, 1.0);
    return max(beyond, kSubpixelCanopy * within);
}

// plant.frag's light for a plant standing along the ground normal (up_normal_blend aside).
vec3 plantLight(vec3 n, float shadow) {
    float sun = clamp(dot(n, frame.sunDirection.xyz) * 0.6 + 0.4, 0.0, 1.0) * shadow * kPlantSunlit;
    return frame.sunRadiance.rgb * sun + ambientLight(n) * kPlantOcclusion;
}

// A rut's soil: compacted by the wheel, darker and smoother (its clods flattened), with a fine grain of its own;
// beside it, the loose soil it pushed out: lighter, drier and crumbly.
void pressRut(inout GroundSample g, float pressed, float loose, float footprint) {
    if (pressed > 0.0) {
        float grain = octaveWeight(0.01, footprint) * (valueNoise(inWorld.xy, 0.01, 90u) - 0.5);
        g.albedo *= (1.0 - kRutDarkening * pressed) * (1.0 + 0.25 * pressed * grain);
        g.slope *= 1.0 - 0.7 * pressed;
    }
    if (loose > 0.0) {
        vec3 crumbs = noiseWithGradient(inWorld.xy, 0.012, 91u);
        float w = loose * octaveWeight(0.012, footprint);
        g.albedo *= 1.0 + loose * 0.18 + w * 0.35 * (crumbs.x - 0.5);
        g.slope += w * 0.4 * 0.012 * crumbs.yz;
    }
}

// Turf pressed into a rut: the thatch flattened, its blades lying along the track and showing their lighter, drier
// faces (a track through a meadow reads lighter than the meadow beside it), with less relief.
void pressTurf(inout GroundSample t, float pressed) {
    t.albedo = mix(t.albedo, mix(t.albedo, vec3(0.26, 0.22, 0.13), 0.3) * 1.15, pressed);
    t.slope *= 1.0 - 0.7 * pressed;
}

// The bare ground's albedo at this pixel and the bump slope of its texture: a mesh ground's material colour times its
// texture, or where a material has no texture, the preset's texture scaled to the material's colour; else the
// scene's preset (terrain.material), blended with the ground materials of the categories growing here.
GroundSample bareGroundHere(float footprint) {
    GroundMaterial m = groundMaterialPreset(tile.material.x);
    if (tile.material.y != 0u) {
        vec2 uv = coverUv(inWorld);
        vec2 at = clamp(uv, vec2(0.0), vec2(1.0));
        vec4 weights = inCoverTile(uv) ? texture(groundMaterialWeights, vec2(at.x, 1.0 - at.y)) : vec4(0.0);
        m = blendGroundMaterials(m, tile.material.z, weights);
    }
    GroundSample g = bareGround(m, inWorld.xy, footprint);
    if (inAlbedo.a > 0.0) {
        if (inUvLayer.z >= 0.0)
            return GroundSample(inAlbedo.rgb * texture(groundTextures, vec3(inUvLayer.xy, round(inUvLayer.z))).rgb,
                                vec2(0.0));
        g.albedo *= inAlbedo.rgb / m.albedo;
    }
    return g;
}

void main() {
#ifdef SWARD_TERRAIN_HOLES
    if (inTrackPatch(inWorld.xy)) discard;
#endif
    if (groundHiddenHere(inWorld.xy, tile.material.w)) discard;
    vec3 n = normalize(inNormal);
    float pressed = clamp(inRut / kRutFullDepth, 0.0, 1.0);
    float footprint = groundFootprint(inWorld);
    // The horizon ring lies beyond the plants' range, where the soil's patches and clods are far below a pixel: its
    // material's mean albedo, without the noise octaves that made most of the ring's cost (render/horizon_ring.h).
    bool ring = tile.material.w == kGroundHorizonRing;
    GroundSample ground = ring ? GroundSample(groundMaterialPreset(tile.material.x).albedo, vec2(0.0))
                               : bareGroundHere(footprint);
    pressRut(ground, pressed, inLoose, footprint);
    float shadow = sunShadow(inWorld);
    vec2 uv = coverUv(inWorld);
    vec4 cover = groundCover(uv);
    float turf = ring ? 0.0 : turfAt(inWorld); // the ring is ground, seen from afar
    if (turf > 0.0) {
        GroundSample t = turfGround(cover.rgb, ground.albedo, inWorld.xy, footprint);
        pressTurf(t, pressed);
        ground.albedo = mix(ground.albedo, t.albedo, turf);
        ground.slope = mix(ground.slope, t.slope, turf);
    }
    vec3 shading = bumpedNormal(n, ground.slope);
    float sun = max(dot(shading, frame.sunDirection.xyz), 0.0) * shadow;
    vec3 color = ground.albedo * (frame.sunRadiance.rgb * sun + ambientLight(shading));
    float weight = inCoverTile(uv) ? coverWeight(inWorld) : 0.0;
    if (weight > 0.0)
        color = mix(color, cover.rgb * kPlantBrightness * plantLight(n, shadow), weight * hiddenFraction(cover.a, inWorld));
    outColor = vec4(aerialPerspective(color, inWorld), 1.0);
}

#endif
