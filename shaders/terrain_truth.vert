#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain in the truth pass: a non-indexed draw of the ground mesh's index count, its vertices and triangle list
// pulled from storage buffers, so every vertex sees its whole triangle and passes on that triangle's geometric
// normal (the smooth vertex normals of the colour pass are not the drawn surface's). Position and planar depth
// are computed exactly as terrain.vert computes them, so depth and labels are the same bits as with its
// vertex-input draw.
#include "shared/frame.glsl"
#include "shared/flow_vertex.glsl"

layout(set = 0, binding = kBindingMeshVertices, std430) readonly buffer VertexBlock { TerrainVertex vertices[]; };
layout(set = 0, binding = kBindingMeshIndices, std430) readonly buffer IndexBlock { uint indices[]; };

layout(location = 0) out vec3 outWorld; // truth.frag's turf label
layout(location = 2) out float outViewDepth;
layout(location = 5) flat out vec3 outNormal; // camera frame, unit, facing the camera
layout(location = 6) out float outRut;         // unpressed (ruts: track.vert)

void main() {
    uint first = uint(gl_VertexIndex) - uint(gl_VertexIndex) % 3u;
    vec3 p0 = vertices[indices[first]].positionHeight.xyz;
    vec3 p1 = vertices[indices[first + 1u]].positionHeight.xyz;
    vec3 p2 = vertices[indices[first + 2u]].positionHeight.xyz;
    vec4 world = vec4(vertices[indices[gl_VertexIndex]].positionHeight.xyz, 1.0);
    gl_Position = frame.viewProj * world;
    outWorld = world.xyz;
    outViewDepth = (frame.view * world).z;
    outNormal = truthNormal(cross(p1 - p0, p2 - p0), p0);
    outRut = 0.0;
    writeFlowVertex(world.xyz, world.xyz); // the ground does not move
}
