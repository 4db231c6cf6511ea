#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shadow casters: alpha-tested depth only.
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"

void main() {
    if (!keepFragment() || texture(atlas, inUv).a < 0.5) discard;
}
