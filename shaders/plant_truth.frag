#version 460
#extension GL_GOOGLE_include_directive : require
// Plant ground truth (1 sample per pixel): the same quads, dither and alpha test at 0.5 as the colour pass.
// Depth and label come from the same fragment, so the masks and the depth map can never disagree.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"

layout(location = 8) flat in uint inTile;

layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, tile label

void main() {
    if (!keepFragment() || texture(atlas, inUv).a < 0.5) discard;
    outDepthBits = floatBitsToUint(inViewDepth);
    outLabel = uvec2(inLabel, inTile);
}
