#version 460
#extension GL_GOOGLE_include_directive : require
// Vegetation expansion, run twice per frame with one workgroup per 5x5 m plant cluster (the "task shader"
// of a mesh-shader pipeline, done in compute because lavapipe has no mesh shaders):
//   WRITE_PASS = 0  count: cull the cluster, choose each plant's LOD(s), store per-LOD counts of the cluster
//   WRITE_PASS = 1  write: same choices, each instance written at clusterOffset[lod] + its rank among the
//                   cluster's plants, so the output order is a pure function of the plant order (no atomic
//                   append order can leak into pixels).
#include "shared/vegetation.glsl"

layout(constant_id = 0) const uint WRITE_PASS = 0;
layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) readonly buffer Statics { PlantStatic statics[]; };
layout(set = 0, binding = 2, std430) readonly buffer Dynamics { PlantDynamic dynamics[]; };
layout(set = 0, binding = 3, std430) readonly buffer Clusters { PlantCluster clusters[]; };
layout(set = 0, binding = 4, std430) readonly buffer Fields { PlantField fields[]; };
layout(set = 0, binding = 5, std430) buffer ClusterCounts { uvec4 clusterCounts[]; }; // count: out, write: offsets in
layout(set = 0, binding = 6, std430) writeonly buffer Instances { PlantInstance instances[]; };

shared uint lodCounts[kLodCount];
shared uvec4 ranks[64]; // per-thread inclusive prefix of (near, mid, far) memberships

float categoryHeight(uint category) {
    return veg.categoryHeight[category];
}

void main() {
    uint cluster = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (cluster >= veg.counts.x) return;
    uint lane = gl_LocalInvocationID.x;
    PlantCluster box = clusters[cluster];
    bool visible = box.range.y > 0u && clusterVisible(box.boundsMin.xyz, box.boundsMax.xyz);
    if (!visible) {
        if (WRITE_PASS == 0u && lane == 0u) clusterCounts[cluster] = uvec4(0u, 0u, 0u, 0u);
        return; // uniform across the workgroup: every lane reads the same cluster
    }
    PlantField field = fields[cluster / veg.counts.y];
    uint first = field.range.x + box.range.x;
    uint count = box.range.y;

    if (lane < kLodCount) lodCounts[lane] = 0u;
    uvec4 base = WRITE_PASS == 1u ? clusterCounts[cluster] : uvec4(0u);
    uvec3 running = uvec3(0u);
    barrier();

    for (uint start = 0u; start < count; start += 64u) {
        uint index = start + lane;
        LodChoice choice = LodChoice(kNoLod, kNoLod, 0.0);
        PlantStatic plant;
        vec3 position = vec3(0.0);
        if (index < count) {
            plant = statics[first + index];
            position = plantPosition(plant, field.originStep);
            choice = chooseLod(distance(position, veg.cameraPosition.xyz));
        }
        uvec3 member = uvec3(0u);
        if (choice.lodA != kNoLod) member[choice.lodA] = 1u;
        if (choice.lodB != kNoLod) member[choice.lodB] = 1u;

        if (WRITE_PASS == 0u) {
            for (uint k = 0u; k < kLodCount; ++k)
                if (member[k] != 0u) atomicAdd(lodCounts[k], 1u); // a sum: order-independent
            continue;
        }

        // Workgroup inclusive scan (Hillis-Steele) of the membership flags: each plant's rank in its chunk.
        ranks[lane] = uvec4(member, 0u);
        barrier();
        for (uint offset = 1u; offset < 64u; offset <<= 1u) {
            uvec4 add = lane >= offset ? ranks[lane - offset] : uvec4(0u);
            barrier();
            ranks[lane] += add;
            barrier();
        }
        uvec3 inclusive = ranks[lane].xyz;
        uvec3 chunkTotal = ranks[63].xyz;
        barrier();

        if (choice.lodA != kNoLod) {
            PlantDynamic dyn = dynamics[first + index];
            float time = veg.windGusts.z;
            float random = plantRandom(plant);
            float cut = plantState(dyn) == kPlantStateCut ? plantCutFraction(dyn) : 1.0;
            float height = categoryHeight(plantCategory(plant)) * plantSizeScale(plant) * cut;
            vec2 tip = plantBend(dyn) + windTip(position, random, time);
            float len = length(tip);
            if (len > 0.95) tip *= 0.95 / len; // a blade bends, it does not stretch
            PlantInstance instance;
            instance.positionHeight = vec4(position, height);
            instance.up = plant.up;
            instance.attributes = plant.attributes;
            instance.tip = packHalf2x16(tip);
            uint cutByte = bitfieldExtract(dyn.state, 24, 8);
            uint fadeBits = uint(clamp(choice.t, 0.0, 1.0) * 65535.0 + 0.5) | (cutByte << 24);
            for (uint k = 0u; k < kLodCount; ++k) {
                if (member[k] == 0u) continue;
                uint slot = base[k] + running[k] + inclusive[k] - 1u;
                if (slot >= veg.counts.z) continue; // capacity exhausted: drop deterministically
                instance.fade = fadeBits | (k == choice.lodB ? 0x10000u : 0u);
                instances[slot] = instance;
            }
        }
        running += chunkTotal;
    }

    if (WRITE_PASS == 0u) {
        barrier();
        if (lane == 0u) clusterCounts[cluster] = uvec4(lodCounts[0], lodCounts[1], lodCounts[2], 1u);
    }
}
