#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain ground truth (1 sample per pixel): the planar depth of the surface at the pixel centre, stored as
// float bits in an R32_UINT attachment, the label (semantic class "ground", no instance) and the triangle's
// normal (terrain_truth.vert). Integer and 32-bit float attachments written without blending hold exactly what
// the shader computed.
#include "shared/frame.glsl"

layout(location = 2) in float inViewDepth;
layout(location = 5) flat in vec3 inNormal;
layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile (a plant's only)
layout(location = 2) out vec4 outNormal; // camera-frame unit normal, w 0

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(kSemanticGround << kInstanceBits, 0u);
    outNormal = vec4(inNormal, 0.0);
}
