#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain in the truth pass: a non-indexed draw of the ground mesh's index count, its vertices and triangle list
// pulled from storage buffers, so every vertex sees its whole triangle and passes on that triangle's geometric
// normal (the smooth vertex normals of the colour pass are not the drawn surface's). Position and planar depth
// are computed exactly as terrain.vert computes them, so depth and labels are the same bits as with its
// vertex-input draw.
#include "shared/frame.glsl"
#include "shared/flow_vertex.glsl"
#include "shared/horizon_ring.glsl"

layout(set = 0, binding = kBindingMeshVertices, std430) readonly buffer VertexBlock { TerrainVertex vertices[]; };
layout(set = 0, binding = kBindingMeshIndices, std430) readonly buffer IndexBlock { uint indices[]; };

layout(location = 0) out vec3 outWorld; // truth.frag's turf label
layout(location = 2) out float outViewDepth;
layout(location = 5) flat out vec3 outNormal; // camera frame, unit, facing the camera
layout(location = 6) out float outRut;         // unpressed (ruts: track.vert)

// terrain.vert's position of vertex v (a horizon ring's rim sunk as there).
vec3 drawnVertex(uint v) {
    return groundVertexPosition(vertices[v].positionHeight, vertices[v].normal, vertices[v].uvLayer);
}

void main() {
    uint first = uint(gl_VertexIndex) - uint(gl_VertexIndex) % 3u;
    vec3 p0 = drawnVertex(indices[first]);
    vec3 p1 = drawnVertex(indices[first + 1u]);
    vec3 p2 = drawnVertex(indices[first + 2u]);
    vec4 world = vec4(drawnVertex(indices[gl_VertexIndex]), 1.0);
    gl_Position = frame.viewProj * world;
    outWorld = world.xyz;
    outViewDepth = (frame.view * world).z;
    outNormal = truthNormal(cross(p1 - p0, p2 - p0), p0);
    outRut = 0.0;
    writeFlowVertex(world.xyz, world.xyz); // the ground does not move
}
