#version 460
#extension GL_GOOGLE_include_directive : require
// Near plants of the grass categories as blades (lod.near_blades; shared/plant_blades.h): one indexed indirect draw
// over the near instances (the blade pattern of the plant index buffer: bladeIndex), every pass. Plants of other
// categories are left to the near cards' draw (their vertices land outside the clip volume). Opaque: no pass
// discards, so the depth test runs before the fragment shader.
#include "shared/frame.glsl"
#include "shared/vegetation.glsl"
#include "shared/plant_vertex.glsl"
#include "shared/plant_blades.glsl"
#include "shared/plant_shading.glsl"
#include "shared/shadow.glsl"
#include "shared/flow_vertex.glsl"

layout(constant_id = 0) const uint PASS = kPassMain; // kPassMain, kPassTruth or kPassShadow

layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Instances { ExpandedPlant instances[]; };
layout(set = 0, binding = kBindingInstancePlants, std430) readonly buffer InstancePlants { uint instancePlants[]; };
layout(set = 0, binding = kBindingAtlas) uniform sampler2D atlas;
#ifdef SWARD_FLOW // the plants' records, and their state at the previous and the next tick
layout(set = 0, binding = kBindingFlowStatics, std430) readonly buffer FlowStatics { PlantStatic flowStatics[]; };
layout(set = 0, binding = kBindingFlowDynamicsPrevious, std430) readonly buffer FlowPrevious {
    PlantDynamic flowDynamicsPrevious[];
};
layout(set = 0, binding = kBindingFlowDynamicsNext, std430) readonly buffer FlowNext {
    PlantDynamic flowDynamicsNext[];
};
#endif

layout(location = 1) out float outViewDepth;
layout(location = 2) out float outHeightFraction;
layout(location = 3) out float outAlong;
layout(location = 4) out vec4 outShadow;       // colour pass: plantShadowCoordinate
layout(location = 5) flat out vec3 outAlbedo;  // colour pass: the blade's albedo at its middle
layout(location = 6) out vec2 outSunTerms;     // colour pass: plantSunLight
layout(location = 7) flat out vec3 outAmbient;
layout(location = 8) flat out vec3 outSunColour;
layout(location = 12) out vec4 outHaze;        // colour pass: hazeAt
layout(location = 9) flat out uint outLabel;   // ground truth: (semantic class << 24) | instance id
layout(location = 10) flat out uint outTile;   // ground truth: the tile's label
layout(location = 11) flat out vec3 outNormal; // ground truth: the triangle's camera-frame normal (truthNormal)

// The blade's albedo: the mean colour of a quarter of its plant's atlas cell (a coarse mip level, alpha-weighted:
// the painted plant's own greens, straws and browns), picked by the blade's hash, with the plant's shading
// (hue and value per plant, felled tint, viewer overlays) and the blade's own value.
vec3 bladeAlbedo(BladePlant p, uint blade, PlantShading shading) {
    uint h = pcgHash(p.key ^ (blade * 0x85EBCA6Bu) ^ 0x1F83D9ABu);
    vec4 rect = cells[p.cell].uvRect;
    float cellTexels = (rect.w - rect.y) * float(textureSize(atlas, 0).y);
    float level = max(log2(max(cellTexels, 1.0)) - 1.0, 0.0); // the cell 2 x 2 texels
    vec2 quarter = vec2(float(h & 1u), float((h >> 1) & 1u)) * 0.5 + 0.25;
    vec3 mean = textureLod(atlas, mix(rect.xy, rect.zw, quarter), level).rgb;
    float value = 0.8 + 0.25 * unitFromHash(pcgHash(h));
    return (shading.albedo * mean + shading.albedoOffset) * value;
}

void main() {
    ExpandedPlant instance = instances[gl_InstanceIndex];
    bool culled = !drawnAsBlades(instance);
    if (PASS == kPassShadow) { // as plant.vert: only the plants that can shade this cascade's shell
        float d = distance(instance.positionHeight.xyz, frame.shadowOrigin.xyz);
        culled = culled || d < frame.shadowParams.y || d > frame.shadowParams.z;
    }
    if (culled) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    uint vertex = uint(gl_VertexIndex), blade = vertex / kBladeVertices;
    BladePlant p = bladePlant(instance);
    BladeShape s = plantBlade(p, blade);
    BladeVertex v = bladeVertex(p, s, vertex);
    outViewDepth = (frame.view * vec4(v.position, 1.0)).z;
    outHeightFraction = v.heightFraction;
    outAlong = v.along;
    outShadow = vec4(0.0);
    outSunTerms = vec2(0.0);
    outSunColour = vec3(0.0);
    outHaze = vec4(0.0);
    outLabel = 0u;
    outTile = 0u;
    outNormal = vec3(0.0);
    if (PASS == kPassTruth) {
        uint state = bitfieldExtract(instance.fade, 17, 4);
        uint semantic = state == kPlantStateFelled ? kSemanticFelled
                      : state == kPlantStateCut    ? kSemanticCut
                                                   : kSemanticVegetation + bitfieldExtract(instance.attributes, 0, 2);
        outLabel = (semantic << kInstanceBits) | (instancePlants[gl_InstanceIndex] + 1u);
        outTile = veg.tile.x;
        outNormal = truthNormal(v.normal, v.position);
#ifdef SWARD_FLOW
        // The same point of the same blade, with the plant's state and wind of the previous and the next tick.
        uint plant = instancePlants[gl_InstanceIndex];
        PlantStatic record = flowStatics[plant];
        BladePlant before = bladePlant(plantAtTick(instance, record, flowDynamicsPrevious[plant], frame.flowTimes.x));
        BladePlant after = bladePlant(plantAtTick(instance, record, flowDynamicsNext[plant], frame.flowTimes.y));
        writeFlowVertex(bladeVertex(before, plantBlade(before, blade), vertex).position,
                        bladeVertex(after, plantBlade(after, blade), vertex).position);
#endif
    }
    if (PASS == kPassMain) {
        uint plant = instancePlants[gl_InstanceIndex];
        float random = float(bitfieldExtract(instance.attributes, 16, 8)) * (1.0 / 255.0);
        PlantShading shading = plantShading(instance.fade, kLodNear, p.up, random, plantColourHash(plant));
        outAlbedo = bladeAlbedo(p, blade, shading);
        outAmbient = shading.ambient;
        // The blade's face on the camera's side; across the tuft along the blade's heading, so a tuft is lit round.
        vec3 toCamera = normalize(veg.cameraPosition.xyz - v.position);
        vec3 face = normalize(v.normal);
        face = dot(face, toCamera) < 0.0 ? -face : face;
        float across = clamp(dot(v.position - p.base, s.outward) / max(0.5 * p.cardWidth, 1e-6), -1.0, 1.0);
        PlantSunLight sun = plantSunLight(face, s.outward, across, p.up, toCamera);
        outSunColour = sun.colour;
        outSunTerms = sun.terms;
        outHaze = hazeAt(v.position);
        outShadow = plantShadowCoordinate(v.position, p.base, plantShadowHash(plant));
    }
    gl_Position = (PASS == kPassShadow ? frame.shadowViewProj : frame.viewProj) * vec4(v.position, 1.0);
}
