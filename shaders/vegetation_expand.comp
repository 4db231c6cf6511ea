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

// Sums over the cluster's plants of categoryCard * height^2 and categoryCard * height per m^2 (sliceHeight's cover2
// and cover1), in plant order.
vec2 clusterCardCover(uint first, uint count, PlantField field) {
    vec2 sums = vec2(0.0);
    for (uint i = 0u; i < count; ++i) {
        float h = plantHeight(statics[first + i], dynamics[first + i]);
        float card = veg.categoryCard[plantCategory(statics[first + i])];
        sums += card * vec2(h * h, h);
    }
    float fieldSize = field.originStep.z * float(kPlantPositionSteps);
    return sums / (fieldSize * fieldSize / float(veg.counts.y));
}

// Sine of the angle between the ray from the plant to the camera and the plant's up: how grazing the view is (far
// slicing and depth merging).
float viewSine(PlantStatic plant, vec3 position) {
    return dot(normalize(veg.cameraPosition.xyz - position), octahedralDecode(plant.up));
}

// The far slicing's cut (ExpandedPlant::attributes bits 24-31; kSliceUnit: hidden whole). Only a plant drawn as a
// far billboard alone is sliced: in a cross-fade band both copies must show the same. `cover.x` < 0 until the
// cluster's sums are first needed.
uint sliceBits(LodChoice choice, PlantStatic plant, float height, vec3 position, uint first, uint count,
               PlantField field, inout vec2 cover) {
    if (choice.lodA != kLodFar || choice.lodB != kNoLod || veg.farLod.x <= 0.0) return 0u;
    if (cover.x < 0.0) cover = clusterCardCover(first, count, field);
    float cut = sliceHeight(veg.farLod.x, cover.x, cover.y, viewSine(plant, position));
    return uint(min(cut / max(height, 1e-6), 1.0) * kSliceUnit);
}

// The far merging's width scale times kWidthScaleUnit (ExpandedPlant::fade bits 8-15; 0: not drawn). Only a plant
// drawn as a far billboard alone is merged: in a cross-fade band both copies must match.
uint widthBits(LodChoice choice, float height, uint category, float dist, uint index) {
    if (choice.lodA != kLodFar || choice.lodB != kNoLod) return uint(kWidthScaleUnit);
    float widthPixels = height * veg.categoryAspect[category] * veg.farLod.z / max(dist, 1e-3);
    return scaleBits(mergeWidthScale(veg.farLod.y, widthPixels, mergeHash(index)));
}

// The far depth merging's scale times kWidthScaleUnit (ExpandedPlant::attributes bits 8-15 of a far billboard; 0: not
// drawn). Like the width, only for a plant drawn as a far billboard alone.
uint depthBits(LodChoice choice, PlantStatic plant, float height, vec3 position, float dist, uint index) {
    if (choice.lodA != kLodFar || choice.lodB != kNoLod) return uint(kWidthScaleUnit);
    float heightPixels = height * veg.farLod.z / max(dist, 1e-3);
    return scaleBits(depthMergeScale(veg.farLod.w, heightPixels, viewSine(plant, position), depthMergeHash(index)));
}

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
    vec2 cover = vec2(-1.0);

    if (WRITE_PASS == 0u) {
        uvec3 lodCounts = uvec3(0u);
        for (uint i = 0u; i < count; ++i) {
            PlantStatic plant = statics[first + i];
            vec3 position = plantPosition(plant, field.originStep);
            float dist = distance(position, camera);
            LodChoice choice = chooseLod(dist);
            if (choice.lodA == kNoLod) continue;
            float height = plantHeight(plant, dynamics[first + i]);
            if (widthBits(choice, height, plantCategory(plant), dist, first + i) == 0u) continue;
            if (depthBits(choice, plant, height, position, dist, first + i) == 0u) continue;
            if (sliceBits(choice, plant, height, position, first, count, field, cover) == uint(kSliceUnit)) continue;
            lodCounts[choice.lodA] += 1u;
            if (choice.lodB != kNoLod) lodCounts[choice.lodB] += 1u;
        }
        // w: plants whose per-plant work was done (statistics; 0 marks a culled cluster)
        clusterCounts[cluster] = uvec4(lodCounts, count);
        return;
    }

    uvec3 slot = clusterCounts[cluster].xyz; // first instance of this cluster in each LOD range
    float time = veg.windGusts.z;
    bool backwards = walkPlantsBackwards(camera.x, camera.y, box.boundsMin.x, box.boundsMin.y, box.boundsMax.x,
                                         box.boundsMax.y); // nearer plants first
    for (uint k = 0u; k < count; ++k) {
        uint i = backwards ? count - 1u - k : k;
        PlantStatic plant = statics[first + i];
        vec3 position = plantPosition(plant, field.originStep);
        float dist = distance(position, camera);
        LodChoice choice = chooseLod(dist);
        if (choice.lodA == kNoLod) continue;
        PlantDynamic dyn = dynamics[first + i];
        float height = plantHeight(plant, dyn);
        uint width = widthBits(choice, height, plantCategory(plant), dist, first + i);
        uint depth = depthBits(choice, plant, height, position, dist, first + i);
        if (width == 0u || depth == 0u) continue;
        uint slice = sliceBits(choice, plant, height, position, first, count, field, cover);
        if (slice == uint(kSliceUnit)) continue;
        ExpandedPlant instance;
        instance.positionHeight = vec4(position, height);
        instance.up = plant.up;
        instance.attributes = bitfieldInsert(plant.attributes, slice, 24, 8);
        if (choice.lodA == kLodFar) instance.attributes = bitfieldInsert(instance.attributes, depth, 8, 8);
        instance.tip = plantTip(plant, dyn, position, time);
        uint fadeBits = uint(clamp(choice.t, 0.0, 1.0) * 255.0 + 0.5) | (width << 8) | plantStateFadeBits(dyn);

        instance.fade = fadeBits;
        if (slot[choice.lodA] < veg.counts.z) { // else: over capacity, dropped (counted by the scan)
            instances[slot[choice.lodA]] = instance;
            instancePlants[slot[choice.lodA]] = first + i;
        }
        slot[choice.lodA] += 1u;
        if (choice.lodB != kNoLod) {
            instance.fade = fadeBits | 0x10000u; // the upper-LOD copy of a plant in a cross-fade band
            if (choice.lodB == kLodFar) instance.attributes = bitfieldInsert(instance.attributes, depth, 8, 8);
            if (slot[choice.lodB] < veg.counts.z) {
                instances[slot[choice.lodB]] = instance;
                instancePlants[slot[choice.lodB]] = first + i;
            }
            slot[choice.lodB] += 1u;
        }
    }
}
