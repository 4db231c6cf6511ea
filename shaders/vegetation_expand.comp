#version 460
#extension GL_GOOGLE_include_directive : require
// Vegetation expansion, run twice per frame with one invocation per 5x5 m plant cluster (the "task shader"
// of a mesh-shader pipeline, done in compute because lavapipe has no mesh shaders):
//   WRITE_PASS = 0  count: cull the cluster, choose each plant's LOD(s), store per-LOD counts of the cluster
//   WRITE_PASS = 1  write: same choices, each instance written at clusterOffset[lod] + its rank among the
//                   cluster's plants, so the output order is a pure function of the plant order (no atomic
//                   append order can leak into pixels).
// One invocation walks its cluster's plants in order: the ranks need no workgroup scan and no barrier, which
// keeps CPU implementations (lavapipe) fast; a cluster holds a few hundred plants, and culled clusters cost
// one box test.
#include "shared/vegetation.glsl"

layout(constant_id = 0) const uint WRITE_PASS = 0;
layout(local_size_x = kExpandGroupSize) in;

layout(set = 0, binding = kExpandBindingStatics, std430) readonly buffer Statics { PlantStatic statics[]; };
layout(set = 0, binding = kExpandBindingDynamics, std430) readonly buffer Dynamics { PlantDynamic dynamics[]; };
layout(set = 0, binding = kExpandBindingClusters, std430) readonly buffer Clusters { PlantCluster clusters[]; };
layout(set = 0, binding = kExpandBindingFields, std430) readonly buffer Fields { PlantField fields[]; };
layout(set = 0, binding = kExpandBindingClusterCounts, std430) buffer ClusterCounts { uvec4 clusterCounts[]; }; // count: out, write: offsets in
layout(set = 0, binding = kExpandBindingInstances, std430) writeonly buffer Instances { ExpandedPlant instances[]; };
// Parallel to instances: the plant's index in the tile's record buffers (ground-truth instance ids).
layout(set = 0, binding = kExpandBindingInstancePlants, std430) writeonly buffer InstancePlants { uint instancePlants[]; };

void main() {
    uint cluster = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * kExpandGroupSize;
    if (cluster >= veg.counts.x) return;
    PlantCluster box = clusters[cluster];
    if (box.range.y == 0u || !clusterVisible(box.boundsMin.xyz, box.boundsMax.xyz)) {
        if (WRITE_PASS == 0u) clusterCounts[cluster] = uvec4(0u);
        return;
    }
    PlantField field = fields[cluster / veg.counts.y];
    uint first = field.range.x + box.range.x;
    uint count = box.range.y;
    vec3 camera = veg.cameraPosition.xyz;

    if (WRITE_PASS == 0u) {
        uvec3 lodCounts = uvec3(0u);
        for (uint i = 0u; i < count; ++i) {
            vec3 position = plantPosition(statics[first + i], field.originStep);
            LodChoice choice = chooseLod(distance(position, camera));
            if (choice.lodA != kNoLod) lodCounts[choice.lodA] += 1u;
            if (choice.lodB != kNoLod) lodCounts[choice.lodB] += 1u;
        }
        // w: plants whose per-plant work was done (statistics; 0 marks a culled cluster)
        clusterCounts[cluster] = uvec4(lodCounts, count);
        return;
    }

    uvec3 slot = clusterCounts[cluster].xyz; // first instance of this cluster in each LOD range
    float time = veg.windGusts.z;
    for (uint i = 0u; i < count; ++i) {
        PlantStatic plant = statics[first + i];
        vec3 position = plantPosition(plant, field.originStep);
        LodChoice choice = chooseLod(distance(position, camera));
        if (choice.lodA == kNoLod) continue;
        PlantDynamic dyn = dynamics[first + i];
        float random = plantRandom(plant);
        float cut = plantState(dyn) == kPlantStateCut ? plantCutFraction(dyn) : 1.0;
        float height = veg.categoryHeight[plantCategory(plant)] * plantSizeScale(plant) * cut;
        vec2 tip = plantBend(dyn) + windTip(position, random, time);
        float len = length(tip);
        if (len > kMaxTipOffset) tip *= kMaxTipOffset / len; // a blade bends, it does not stretch
        ExpandedPlant instance;
        instance.positionHeight = vec4(position, height);
        instance.up = plant.up;
        instance.attributes = plant.attributes;
        instance.tip = packHalf2x16(tip);
        uint fadeBits = uint(clamp(choice.t, 0.0, 1.0) * 65535.0 + 0.5) | (plantState(dyn) << 17) |
                        (bitfieldExtract(dyn.state, 24, 8) << 24);

        instance.fade = fadeBits;
        if (slot[choice.lodA] < veg.counts.z) { // else: over capacity, dropped (counted by the scan)
            instances[slot[choice.lodA]] = instance;
            instancePlants[slot[choice.lodA]] = first + i;
        }
        slot[choice.lodA] += 1u;
        if (choice.lodB != kNoLod) {
            instance.fade = fadeBits | 0x10000u; // the upper-LOD copy of a plant in a cross-fade band
            if (slot[choice.lodB] < veg.counts.z) {
                instances[slot[choice.lodB]] = instance;
                instancePlants[slot[choice.lodB]] = first + i;
            }
            slot[choice.lodB] += 1u;
        }
    }
}
