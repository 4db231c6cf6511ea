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

// The stored vertex at a corner of the drawn grid: its level of detail draws every (1 << level)-th vertex.
uint patchVertex(uint entry, uvec2 corner) {
    uint level = entry >> kTrackLodShift, patchIndex = entry & ((1u << kTrackLodShift) - 1u);
    uvec2 stored = corner << level;
    return patchIndex * kTrackPatchVertices * kTrackPatchVertices + stored.y * kTrackPatchVertices + stored.x;
}

void main() {
    uint entry = visiblePatches[gl_InstanceIndex];
    uint cellsPerSide = (kTrackPatchVertices - 1u) >> (entry >> kTrackLodShift);
    TerrainVertex v;
    uvec2 c0, c1, c2;
    if (PASS == kPassMain) { // indexed: gl_VertexIndex is a vertex of the level's grid, row by row
        uint side = cellsPerSide + 1u;
        v = vertices[patchVertex(entry, uvec2(uint(gl_VertexIndex) % side, uint(gl_VertexIndex) / side))];
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
