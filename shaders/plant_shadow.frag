#version 460
#extension GL_GOOGLE_include_directive : require
// Plant shadow casters: alpha-tested depth only, at the atlas level the cascade's texel size picks (plantShadowAlpha).
#include "shared/frame.glsl"
#include "shared/plant_fragment.glsl"

void main() {
    if (!keepFragment() || plantShadowAlpha(int(frame.shadowParams.w)) < 0.5) discard;
}
