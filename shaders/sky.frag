#version 460
#extension GL_GOOGLE_include_directive : require
// Sky: horizon-to-zenith gradient plus an HDR sun disc. Ground-truth depth keeps its clear value (+inf).
#include "shared/frame.glsl"

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

void main() {
    vec4 far = frame.invViewProj * vec4(inNdc, 1e-7, 1.0); // a point far along the pixel's ray
    vec3 dir = normalize(far.xyz / far.w - frame.cameraPosition.xyz);
    vec3 color = skyRadiance(dir);
    float sunCos = dot(dir, frame.sunDirection.xyz);
    if (sunCos > 0.99996) color += frame.sunRadiance.rgb * 2000.0; // ~0.5 degree disc, HDR
    outColor = vec4(color, 1.0);
}
