#version 460
#extension GL_GOOGLE_include_directive : require
// A rut patch (render/track_renderer.h): instance k draws the k-th entry of visiblePatches (slot | level <<
// kTrackLodShift), a grid of kTrackPatchVertices^2 vertices pulled from storage, every (1 << level)-th of them drawn,
// two triangles per cell split along (i, j)-(i+1, j+1) and wound counter-clockwise seen from above, as the
// heightfield's: indexed in the main pass, three vertices per triangle in the truth pass (for its normal). Outputs are
// terrain.vert's, for terrain.frag, and terrain_truth.vert's, for truth.frag; the rut depth (position w) goes to both,
// for the compacted soil's colour and the "track" label.
#include "shared/frame.glsl"
#include "shared/flow_vertex.glsl"

layout(constant_id = 0) const uint PASS = kPassMain; // kPassMain or kPassTruth

layout(set = 0, binding = kBindingMeshVertices, std430) readonly buffer PatchBlock { TerrainVertex vertices[]; };
layout(set = 0, binding = kBindingMeshIndices, std430) readonly buffer VisibleBlock { uint visiblePatches[]; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec4 outAlbedo;
layout(location = 4) out vec3 outUvLayer;
layout(location = 5) flat out vec3 outTriangleNormal; // camera frame, unit, facing the camera (truth pass)
layout(location = 6) out float outRut;
layout(location = 7) out float outLoose; // soil the wheel pushed up beside the rut (terrain_fragment.glsl)

// The stored vertex at a corner of the drawn grid: its level of detail draws every (1 << level)-th vertex.
uint patchVertex(uint entry, uvec2 corner) {
    uint level = entry >> kTrackLodShift, patchIndex = entry & ((1u << kTrackLodShift) - 1u);
    uvec2 stored = corner << level;
    return patchIndex * kTrackPatchVertices * kTrackPatchVertices + stored.y * kTrackPatchVertices + stored.x;
}

// Loose soil beside a rut: an unpressed vertex within two cells of a pressed one holds the soil pushed out of it, in
// proportion to the deepest rut there (full from 1 cm). Only the colour uses it: the surface stays the lattice's.
float looseSoil(uint entry, uvec2 corner, float rut) {
    if (rut > 0.0) return 0.0;
    uint base = (entry & ((1u << kTrackLodShift) - 1u)) * kTrackPatchVertices * kTrackPatchVertices;
    ivec2 stored = ivec2(corner << (entry >> kTrackLodShift));
    float nearest = 0.0;
    const ivec2 offsets[8] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1), ivec2(2, 0), ivec2(-2, 0),
                                     ivec2(0, 2), ivec2(0, -2));
    for (int k = 0; k < 8; ++k) {
        ivec2 p = clamp(stored + offsets[k], ivec2(0), ivec2(int(kTrackPatchVertices) - 1));
        nearest = max(nearest, vertices[base + uint(p.y) * kTrackPatchVertices + uint(p.x)].positionHeight.w);
    }
    return clamp(nearest / 0.01, 0.0, 1.0);
}

void main() {
    uint entry = visiblePatches[gl_InstanceIndex];
    uint cellsPerSide = (kTrackPatchVertices - 1u) >> (entry >> kTrackLodShift);
    TerrainVertex v;
    uvec2 c0, c1, c2;
    float loose = 0.0;
    if (PASS == kPassMain) { // indexed: gl_VertexIndex is a vertex of the level's grid, row by row
        uint side = cellsPerSide + 1u;
        uvec2 corner = uvec2(uint(gl_VertexIndex) % side, uint(gl_VertexIndex) / side);
        v = vertices[patchVertex(entry, corner)];
        loose = looseSoil(entry, corner, v.positionHeight.w);
    } else { // three vertices per triangle, in the main pass's index order (render/track_renderer.cpp)
        uint triangle = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
        uvec2 cell = uvec2((triangle / 2u) % cellsPerSide, (triangle / 2u) / cellsPerSide);
        bool upper = (triangle & 1u) != 0u;
        c0 = cell;
        c1 = cell + (upper ? uvec2(1u, 1u) : uvec2(1u, 0u));
        c2 = cell + (upper ? uvec2(0u, 1u) : uvec2(1u, 1u));
        v = vertices[patchVertex(entry, corner == 0u ? c0 : corner == 1u ? c1 : c2)];
    }
    vec4 world = vec4(v.positionHeight.xyz, 1.0);
    gl_Position = frame.viewProj * world;
    outWorld = world.xyz;
    outNormal = v.normal.xyz;
    outViewDepth = (frame.view * world).z;
    outAlbedo = v.albedo;
    outUvLayer = v.uvLayer.xyz;
    outRut = v.positionHeight.w;
    outLoose = loose;
    outTriangleNormal = vec3(0.0);
    if (PASS == kPassTruth) {
        vec3 p0 = vertices[patchVertex(entry, c0)].positionHeight.xyz,
             p1 = vertices[patchVertex(entry, c1)].positionHeight.xyz,
             p2 = vertices[patchVertex(entry, c2)].positionHeight.xyz;
        outTriangleNormal = truthNormal(cross(p1 - p0, p2 - p0), p0);
        // A rut is pressed where a wheel stands, which hides it: its ground is taken as still, as the rest.
        writeFlowVertex(world.xyz, world.xyz);
    }
}
