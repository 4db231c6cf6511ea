#version 460
#extension GL_GOOGLE_include_directive : require
// Scene object ground truth (1 sample per pixel): planar depth bits, the object's label
// ((kSemanticObject << kInstanceBits) | (kInstanceObjectBase + object index)) and the triangle's normal
// (object_truth.vert), as truth.frag does for terrain.
#include "shared/frame.glsl"
#include "shared/flow_fragment.glsl"

layout(location = 2) in float inViewDepth;
layout(location = 4) flat in uint inLabel;
layout(location = 5) flat in vec3 inNormal;

layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile
layout(location = 2) out vec4 outNormal; // camera-frame unit normal, w 0

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(inLabel, 0u);
    outNormal = vec4(inNormal, 0.0);
    writeFlowFragment();
}
