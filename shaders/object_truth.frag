#version 460
#extension GL_GOOGLE_include_directive : require
// Scene object ground truth (1 sample per pixel): planar depth bits and the object's label
// ((kSemanticObject << kInstanceBits) | (kInstanceObjectBase + object index)), as truth.frag does for terrain.
#include "shared/frame.glsl"

layout(location = 2) in float inViewDepth;
layout(location = 4) flat in uint inLabel;

layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(inLabel, 0u);
}
