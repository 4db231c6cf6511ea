#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain ground truth (1 sample per pixel): the planar depth of the surface at the pixel centre, stored as
// float bits in an R32_UINT attachment, the label (semantic class "turf" where terrain.frag shades turf at this
// point, else "ground"; no instance) and the triangle's normal (terrain_truth.vert). Integer and 32-bit float attachments written without blending hold exactly what
// the shader computed.
#include "shared/frame.glsl"
#include "shared/ground_cover.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 2) in float inViewDepth;
layout(location = 5) flat in vec3 inNormal;
layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile (a plant's only)
layout(location = 2) out vec4 outNormal; // camera-frame unit normal, w 0

void main() {
    outDepthBits = floatBitsToUint(inViewDepth);
    bool turf = turfFraction(groundCover(coverUv(inWorld)).a) >= 0.5;
    outLabel = uvec2((turf ? kSemanticTurf : kSemanticGround) << kInstanceBits, 0u);
    outNormal = vec4(inNormal, 0.0);
}
