#version 460
#extension GL_GOOGLE_include_directive : require
// Bakes the vertices of one LOD's instances into a static vertex buffer (the exact math of plant.vert and, with lod
// kLodCount, of plant_blade.vert's near blades). Used by benchmarks (draw the very same quads without expansion) and
// by the CPU-reference tests. What a draw leaves out (the near cards of plants drawn as blades, the blades of other
// plants) is baked as degenerate triangles at the plant's base.
#include "shared/vegetation.glsl"
#include "shared/plant_vertex.glsl"
#include "shared/plant_blades.glsl"

layout(local_size_x = kComputeGroupSize) in;
layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Instances { ExpandedPlant instances[]; };
layout(set = 0, binding = kBindingBakedVertices, std430) writeonly buffer Baked { BakedVertex baked[]; };
layout(push_constant) uniform Push { BakeConstants push; };

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * kComputeGroupSize;
    if (i >= push.vertexCount) return;
    bool blades = push.lod == kLodCount;
    uint verticesPerPlant = blades ? veg.options.y * kBladeIndices : plantVertexCount(push.lod, veg.options.x);
    ExpandedPlant instance = instances[push.firstInstance + i / verticesPerPlant];
    uint k = i % verticesPerPlant;
    if (blades || (push.lod == kLodNear && drawnAsBlades(instance))) {
        vec3 position = instance.positionHeight.xyz;
        float fraction = 0.0;
        if (blades && drawnAsBlades(instance)) { // vertex k of the plant's unindexed blade draw
            BladePlant p = bladePlant(instance);
            uint vertex = bladeIndex(k);
            BladeVertex v = bladeVertex(p, plantBlade(p, vertex / kBladeVertices), vertex);
            position = v.position;
            fraction = v.heightFraction;
        }
        baked[push.firstVertex + i] = BakedVertex(vec4(position, fraction), vec4(0.0),
                                                  uvec4(instance.up, instance.fade, 0u, 0u));
        return;
    }
    // Vertex k of the plant's unindexed draw: fan vertex k % perQuad of quad k / perQuad.
    uint cell, perQuad = quadVertexCount(push.lod, veg.options.x);
    PlantQuad q = plantQuad(instance, push.lod, k / perQuad, veg.cameraPosition.xyz, cell);
    PlantVertex v = quadCorner(instance, q, cell, push.lod, fanCorner(k % perQuad));
    // Static vertices carry atlas coordinates: a merged billboard shows its plant stretched (a timing baseline).
    vec2 uv = mix(q.uvRect.xy, q.uvRect.zw, vec2(v.uv.x / q.repeat, v.uv.y));
    baked[push.firstVertex + i] = BakedVertex(vec4(v.position, v.heightFraction), vec4(uv, v.random, 0.0),
                                              uvec4(instance.up, instance.fade, 0u, 0u));
}
