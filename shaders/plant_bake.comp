#version 460
#extension GL_GOOGLE_include_directive : require
// Bakes the vertices of one LOD's instances into a static vertex buffer (the exact math of plant.vert).
// Used by benchmarks (draw the very same quads without expansion) and by the CPU-reference test.
#include "shared/vegetation.glsl"
#include "shared/plant_vertex.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 2, std430) readonly buffer Instances { ExpandedPlant instances[]; };
layout(set = 0, binding = 4, std430) writeonly buffer Baked { BakedVertex baked[]; };
layout(push_constant) uniform Push {
    uint lod;
    uint firstInstance;
    uint firstVertex; // output offset
    uint vertexCount; // instances * 6 * quads(lod)
} push;

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
    if (i >= push.vertexCount) return;
    uint verticesPerPlant = push.lod == kLodNear ? 24u : push.lod == kLodMid ? 12u : 6u;
    ExpandedPlant instance = instances[push.firstInstance + i / verticesPerPlant];
    PlantVertex v = plantVertex(instance, push.lod, i % verticesPerPlant);
    baked[push.firstVertex + i] = BakedVertex(vec4(v.position, v.heightFraction), vec4(v.uv, v.random, 0.0),
                                              uvec4(instance.up, instance.fade, 0u, 0u));
}
