#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shadow casters: alpha-tested depth only.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"

void main() {
    float alpha = plantTexel().a; // before any discard: its mip level needs the whole 2x2 quad
    if (!keepFragment() || alpha < 0.5) discard;
}
