// Per-frame constants block (set 0, binding kBindingFrame) and common helpers, included by every render shader.
#ifndef SWARD_FRAME_GLSL
#define SWARD_FRAME_GLSL

#include "config.h"
#include "gpu_layout.h"

layout(set = 0, binding = kBindingFrame, std140) uniform FrameBlock {
    FrameConstants frame;
};

// Hemisphere sky light arriving along unit direction `dir` (z up), shared by the sky and ambient light.
vec3 skyRadiance(vec3 dir) {
    float up = clamp(dir.z, -1.0, 1.0);
    if (up < 0.0) return mix(frame.skyHorizon.rgb, frame.groundAmbient.rgb, min(-up * 4.0, 1.0));
    return mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, sqrt(up));
}

// Irradiance-like ambient term for a surface with unit normal n: sky from above, bounce light from below.
vec3 ambientLight(vec3 n) {
    return mix(frame.groundAmbient.rgb, 0.5 * (frame.skyZenith.rgb + frame.skyHorizon.rgb), 0.5 + 0.5 * n.z);
}

// Ground-truth normal of a triangle (truth pass): `worldNormal` is its geometric normal in world space, any length
// (the cross product of two world-space edges: differences of nearby vertex floats are exact, so this is the
// drawn triangle's own plane, whatever the distance from the origin); `worldPoint` is one of its vertices. Returns
// the unit normal in the camera frame (OpenCV axes, as frame.view) turned towards the camera (n . p < 0 for the
// triangle's points p, which all lie on one side of the camera).
vec3 truthNormal(vec3 worldNormal, vec3 worldPoint) {
    vec3 n = normalize(mat3(frame.view) * worldNormal);
    vec3 p = (frame.view * vec4(worldPoint, 1.0)).xyz;
    return dot(n, p) > 0.0 ? -n : n;
}

#endif
