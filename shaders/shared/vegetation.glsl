// Vegetation expansion helpers shared by the compute passes and the plant shaders: level-of-detail choice with
// cross-fade bands, cluster culling and procedural wind. Everything here is a pure function of its inputs and
// the simulation time, so a frame is reproducible from (scene, seed, tick).
#ifndef SWARD_VEGETATION_GLSL
#define SWARD_VEGETATION_GLSL

#include "config.h"
#include "gpu_layout.h"
#include "plant_layout.h"
#include "plant_decode.glsl"

layout(set = 0, binding = kBindingVegetation, std140) uniform VegetationBlock {
    VegetationConstants veg;
};

const uint kNoLod = 0xffffffffu;

// A plant is drawn in lodA; inside a cross-fade band also in lodB. Per pixel exactly one of the two copies
// survives the dither test (see keepFragment), so the switch is a dissolve over the band, never a pop.
struct LodChoice {
    uint lodA;
    uint lodB; // kNoLod outside bands (and in the band at the far limit, where the plant dissolves)
    float t;   // 0 = all lodA, 1 = all lodB (or gone)
};

LodChoice chooseLod(float distance) {
    float band = max(veg.lodDistances.w, 1e-3), half_ = 0.5 * band;
    float d0 = veg.lodDistances.x, d1 = veg.lodDistances.y, d2 = veg.lodDistances.z;
    if (distance >= d2 + half_) return LodChoice(kNoLod, kNoLod, 0.0);
    if (distance < d0 - half_) return LodChoice(kLodNear, kNoLod, 0.0);
    if (distance < d0 + half_) return LodChoice(kLodNear, kLodMid, (distance - (d0 - half_)) / band);
    if (distance < d1 - half_) return LodChoice(kLodMid, kNoLod, 0.0);
    if (distance < d1 + half_) return LodChoice(kLodMid, kLodFar, (distance - (d1 - half_)) / band);
    if (distance < d2 - half_) return LodChoice(kLodFar, kNoLod, 0.0);
    return LodChoice(kLodFar, kNoLod, (distance - (d2 - half_)) / band);
}

// Conservative box test against the camera frustum (near + 4 side planes; the far plane is at infinity) and
// against the far limit of the vegetation.
bool clusterVisible(vec3 lo, vec3 hi) {
    for (int i = 0; i < 5; ++i) {
        vec4 plane = veg.frustumPlanes[i];
        vec3 farthest = mix(lo, hi, greaterThan(plane.xyz, vec3(0.0)));
        if (dot(plane.xyz, farthest) + plane.w < 0.0) return false;
    }
    vec3 nearest = clamp(veg.cameraPosition.xyz, lo, hi);
    return distance(nearest, veg.cameraPosition.xyz) < veg.lodDistances.z + 0.5 * veg.lodDistances.w;
}

// Procedural wind as a horizontal tip offset in plant heights: a steady lean, gusts travelling downwind as
// waves, and per-plant sway whose phase and speed come from the plant's random value.
vec2 windTip(vec3 position, float random, float time) {
    vec2 dir = veg.wind.xy;
    float phase = random * 6.2831853;
    float speed = 0.8 + 0.4 * random;
    float sway = sin(time * 2.1 * speed + phase + dot(position.xy, vec2(0.21, 0.13)));
    float travel = dot(position.xy, dir) / max(veg.windGusts.y, 1.0);
    float wave = max(sin(6.2831853 * (veg.wind.w * time - travel)), 0.0);
    float gust = veg.windGusts.x * wave * wave;
    float flutter = veg.windGusts.w * sin(time * 6.3 * speed + phase * 3.0);
    return dir * (veg.wind.z * (0.8 + 0.2 * sway) + gust) + vec2(-dir.y, dir.x) * flutter;
}

// A plant's height after its size and cut (what the draw uses).
float plantHeight(PlantStatic plant, PlantDynamic dyn) {
    float cut = plantState(dyn) == kPlantStateCut ? plantCutFraction(dyn) : 1.0;
    return veg.categoryHeight[plantCategory(plant)] * plantSizeScale(plant) * cut;
}

// ExpandedPlant::tip: the interaction's bend plus the wind at `time`, at most kMaxTipOffset (a blade bends, it does
// not stretch).
uint plantTip(PlantStatic plant, PlantDynamic dyn, vec3 position, float time) {
    vec2 tip = plantBend(dyn) + windTip(position, plantRandom(plant), time);
    float len = length(tip);
    if (len > kMaxTipOffset) tip *= kMaxTipOffset / len;
    return packHalf2x16(tip);
}

// ExpandedPlant::fade bits 17-20 (the plant's state) and 24-31 (its cut height byte).
uint plantStateFadeBits(PlantDynamic dyn) {
    return (plantState(dyn) << 17) | (bitfieldExtract(dyn.state, 24, 8) << 24);
}

// `instance` (expanded at this tick) with the state `dyn` of another tick and the wind at that tick's `time`: the
// same plant in the same level of detail, cross-fade, slicing and merging, bent, felled or cut as at that tick.
// The motion ground truth places each drawn point on it (plant.vert with SWARD_FLOW).
ExpandedPlant plantAtTick(ExpandedPlant instance, PlantStatic plant, PlantDynamic dyn, float time) {
    instance.positionHeight.w = plantHeight(plant, dyn);
    instance.tip = plantTip(plant, dyn, instance.positionHeight.xyz, time);
    instance.fade = (instance.fade & 0x1ffffu) | plantStateFadeBits(dyn);
    return instance;
}

#endif
