#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain ground truth (1 sample per pixel): the planar depth of the surface at the pixel centre, stored as
// float bits in an R32_UINT attachment, and the label (semantic class "ground", no instance). Integer
// attachments are never filtered or blended, so the values read back are exactly what the shader computed.
#include "shared/frame.glsl"

layout(location = 2) in float inViewDepth;
layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile (a plant's only)

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(kSemanticGround << kInstanceBits, 0u);
}
