#version 460
#extension GL_GOOGLE_include_directive : require
// sward-view overlay lines (field rectangles, cluster boxes, collider wireframes) in the main HDR pass.
#include "shared/frame.glsl"

layout(location = 0) in vec4 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec3 outColor;

void main() {
    outColor = inColor.rgb;
    gl_Position = frame.viewProj * vec4(inPosition.xyz, 1.0);
}
