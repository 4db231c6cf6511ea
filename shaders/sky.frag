#version 460
#extension GL_GOOGLE_include_directive : require
// Sky: the physical model or the scene's gradient (frame.glsl skyRadiance), optional procedural cumulus, and an HDR
// sun disc. Ground-truth depth keeps its clear value (+inf).
#include "shared/frame.glsl"
#include "shared/hash_noise.glsl"

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

// The clouds' layer: a plane this high above the camera, its noise this coarse (metres).
const float kCloudHeight = 1500.0;
const float kCloudCell = 1200.0;

// Cumulus over the sky `color` along `dir`: four octaves of hashed value noise on the cloud plane (hash_noise.glsl:
// the same on every device), covering the sky where they exceed 1 - cover; lit by the sun above, greyer below,
// fading into the haze towards the horizon.
vec3 clouds(vec3 dir, vec3 color, float cover) {
    if (dir.z <= 0.01) return color;
    vec2 p = frame.cameraPosition.xy + dir.xy * (kCloudHeight / dir.z);
    float n = 0.0, amplitude = 0.5, cell = kCloudCell;
    for (uint octave = 0u; octave < 4u; ++octave, amplitude *= 0.5, cell *= 0.5)
        n += amplitude * valueNoise(p, cell, 0x51u + octave);
    n /= 0.9375; // the octaves' amplitudes' sum
    float density = smoothstep(1.0 - cover, min(1.0 - cover + 0.3, 1.0), n);
    vec3 lit = frame.sunRadiance.rgb * mix(0.28, 0.4, n) * max(frame.sunDirection.z, 0.1) + frame.skyAmbient.rgb * 0.6;
    float horizonFade = smoothstep(0.01, 0.15, dir.z);
    return mix(color, lit, density * horizonFade);
}

void main() {
    vec4 far = frame.invViewProj * vec4(inNdc, 1e-7, 1.0); // a point far along the pixel's ray
    vec3 dir = normalize(far.xyz / far.w - frame.cameraPosition.xyz);
    vec3 color = skyRadiance(dir);
    if (frame.skyParams.z > 0.0) color = clouds(dir, color, frame.skyParams.z);
    float sunCos = dot(dir, frame.sunDirection.xyz);
    if (sunCos > 0.99996) color += frame.sunRadiance.rgb * 2000.0; // ~0.5 degree disc, HDR
    outColor = vec4(color, 1.0);
}
