#version 460
#extension GL_GOOGLE_include_directive : require
// Bakes the vertices of one LOD's instances into a static vertex buffer (the exact math of plant.vert).
// Used by benchmarks (draw the very same quads without expansion) and by the CPU-reference test.
#include "shared/vegetation.glsl"
#include "shared/plant_vertex.glsl"

layout(local_size_x = kComputeGroupSize) in;
layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Instances { ExpandedPlant instances[]; };
layout(set = 0, binding = kBindingBakedVertices, std430) writeonly buffer Baked { BakedVertex baked[]; };
layout(push_constant) uniform Push { BakeConstants push; };

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * kComputeGroupSize;
    if (i >= push.vertexCount) return;
    uint verticesPerPlant = plantVertexCount(push.lod, veg.options.x);
    ExpandedPlant instance = instances[push.firstInstance + i / verticesPerPlant];
    // Vertex k of the plant's unindexed draw: fan vertex k % perQuad of quad k / perQuad.
    uint k = i % verticesPerPlant, cell, perQuad = quadVertexCount(push.lod, veg.options.x);
    PlantQuad q = plantQuad(instance, push.lod, k / perQuad, veg.cameraPosition.xyz, cell);
    PlantVertex v = quadCorner(instance, q, cell, push.lod, fanCorner(k % perQuad));
    // Static vertices carry atlas coordinates: a merged billboard shows its plant stretched (a timing baseline).
    vec2 uv = mix(q.uvRect.xy, q.uvRect.zw, vec2(v.uv.x / q.repeat, v.uv.y));
    baked[push.firstVertex + i] = BakedVertex(vec4(v.position, v.heightFraction), vec4(uv, v.random, 0.0),
                                              uvec4(instance.up, instance.fade, 0u, 0u));
}
