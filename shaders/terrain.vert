#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain: the static ground mesh (heightfield grid or the scene's glTF ground), positions already in world space.
#include "shared/frame.glsl"
#include "shared/horizon_ring.glsl"

layout(constant_id = 0) const uint PASS = kPassMain; // kPassMain or kPassShadow (truth: terrain_truth.vert)

layout(location = 0) in vec4 inPosition;
layout(location = 1) in vec4 inNormal;
layout(location = 2) in vec4 inAlbedo;
layout(location = 3) in vec4 inUvLayer;

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec4 outAlbedo;
layout(location = 4) out vec3 outUvLayer;
layout(location = 6) out float outRut; // unpressed: ruts are drawn as patches of their own (track.vert)
layout(location = 7) out float outLoose;

void main() {
    vec4 world = vec4(groundVertexPosition(inPosition, inNormal, inUvLayer), 1.0);
    gl_Position = (PASS == kPassShadow ? frame.shadowViewProj : frame.viewProj) * world;
    outWorld = world.xyz;
    outNormal = inNormal.xyz;
    outAlbedo = inAlbedo;
    outUvLayer = inUvLayer.xyz;
    outRut = 0.0;
    outLoose = 0.0;
    // Planar depth along the optical axis: view space uses OpenCV camera axes (z forward).
    outViewDepth = (frame.view * world).z;
}
