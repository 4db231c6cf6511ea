#version 460
#extension GL_GOOGLE_include_directive : require
// Terrain shading: a mesh ground's material colour, or soil / dry-grass albedo varied by slope and height, sun (Lambert) + hemispherical ambient.
#include "shared/frame.glsl"
#include "shared/shadow.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inViewDepth;
layout(location = 3) in vec4 inAlbedo;

layout(location = 0) out vec4 outColor;

void main() {
    vec3 n = normalize(inNormal);
    float slope = 1.0 - n.z;
    // Dark turf: under the vegetation the ground reads as the dense base of the sward, not as bare soil.
    vec3 soil = vec3(0.16, 0.12, 0.07);
    vec3 turf = vec3(0.07, 0.10, 0.03);
    // Low-frequency variation from position only (no texture): keeps large flat areas from looking uniform.
    float variation = 0.5 + 0.5 * sin(inWorld.x * 0.071 + 1.3 * sin(inWorld.y * 0.053));
    vec3 albedo = mix(turf, soil, clamp(slope * 4.0 + 0.25 * variation, 0.0, 1.0));
    // A mesh ground is drawn with its materials' base colours.
    if (inAlbedo.a > 0.0) albedo = inAlbedo.rgb;
    float sun = max(dot(n, frame.sunDirection.xyz), 0.0) * sunShadow(inWorld);
    vec3 light = frame.sunRadiance.rgb * sun + ambientLight(n);
    outColor = vec4(albedo * light, 1.0);
}
