#version 460
#extension GL_GOOGLE_include_directive : require
// Blade ground truth (plant_blade.vert): depth, label and the triangle's normal of the nearest blade, and with
// SWARD_FLOW its flow. Opaque, as the colour pass draws it: no discard.
#include "shared/frame.glsl"
#include "shared/flow_fragment.glsl"

layout(location = 1) in float inViewDepth;
layout(location = 9) flat in uint inLabel;
layout(location = 10) flat in uint inTile;
layout(location = 11) flat in vec3 inNormal;

layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, tile label
layout(location = 2) out vec4 outNormal; // the triangle's camera-frame unit normal, w 0

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(inLabel, inTile);
    outNormal = vec4(inNormal, 0.0);
    writeFlowFragment();
}
