#version 460
#extension GL_GOOGLE_include_directive : require
// Plant ground truth (1 sample per pixel): the same quads, dither and alpha test at 0.5 as the colour pass.
// Depth, label and normal come from the same fragment, so the masks, depth map and normals can never disagree.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"
#include "shared/flow_fragment.glsl"

layout(location = 8) flat in uint inTile;
layout(location = 9) flat in vec3 inNormal;

layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, tile label
layout(location = 2) out vec4 outNormal; // the triangle's camera-frame unit normal (plant.vert), w 0

void main() {
    float alpha = plantTexel().a; // before any discard: its mip level needs the whole 2x2 quad
    if (!keepFragment() || alpha < 0.5) discard;
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(inLabel, inTile);
    outNormal = vec4(inNormal, 0.0);
    writeFlowFragment();
}
