#version 460
#extension GL_GOOGLE_include_directive : require
// Ground-truth pass (1 sample per pixel): the planar depth of the surface at the pixel centre, stored as
// float bits in an R32_UINT attachment. Integer attachments are never filtered or blended, so the value
// read back is exactly what the shader computed.
#include "shared/frame.glsl"

layout(location = 2) in float inViewDepth;
layout(location = 0) out uint outDepthBits;

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
}
