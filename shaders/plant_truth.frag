#version 460
#extension GL_GOOGLE_include_directive : require
// Plant ground truth (1 sample per pixel): the same quads, dither and alpha test at 0.5 as the colour pass.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"

layout(location = 0) out uint outDepthBits;

void main() {
    if (!keepFragment() || texture(atlas, inUv).a < 0.5) discard;
    outDepthBits = floatBitsToUint(inViewDepth);
}
