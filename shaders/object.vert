#version 460
#extension GL_GOOGLE_include_directive : require
// Scene objects (glTF models): node-frame vertices moved by their node's per-frame world transform.
#include "shared/frame.glsl"
#include "shared/object_layout.h"

layout(constant_id = 0) const uint PASS = kPassMain; // kPassMain or kPassShadow (truth: object_truth.vert)

layout(set = 0, binding = kBindingObjectTransforms, std430) readonly buffer TransformBlock {
    ObjectTransform transforms[];
};

layout(location = 0) in vec4 inPosition;
layout(location = 1) in vec4 inNormal;
layout(location = 2) in vec4 inBaseColor;
layout(location = 3) in uvec4 inInfo;

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec3 outBaseColor;
layout(location = 4) flat out uint outLabel;

void main() {
    ObjectTransform t = transforms[inInfo.x];
    vec4 world = t.worldFromNode * vec4(inPosition.xyz, 1.0);
    gl_Position = (PASS == kPassShadow ? frame.shadowViewProj : frame.viewProj) * world;
    outWorld = world.xyz;
    outNormal = mat3(t.normalFromNode) * inNormal.xyz;
    // Planar depth along the optical axis (OpenCV camera axes, z forward), as the terrain's.
    outViewDepth = (frame.view * world).z;
    outBaseColor = inBaseColor.rgb;
    outLabel = inInfo.y;
}
