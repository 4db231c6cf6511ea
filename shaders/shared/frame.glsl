// Per-frame constants block (set 0, binding kBindingFrame) and common helpers, included by every render shader.
#ifndef SWARD_FRAME_GLSL
#define SWARD_FRAME_GLSL

#include "config.h"
#include "gpu_layout.h"

layout(set = 0, binding = kBindingFrame, std140) uniform FrameBlock {
    FrameConstants frame;
};

// CIE xyY (Y: luminance) to linear sRGB (Rec. 709, D65), as world/sky.cpp's xyYToLinearSrgb.
vec3 xyYToLinearRgb(float x, float y, float luminance) {
    vec3 xyz = vec3(x, y, 1.0 - x - y) * (luminance / max(y, 1e-6));
    return max(mat3(3.2406, -0.9689, 0.0557, -1.5372, 1.8758, -0.2040, -0.4986, 0.0415, 1.0570) * xyz, 0.0);
}

// The physical sky (world/sky.h, Preetham) along unit direction `dir` (z up): Perez's F(theta, gamma) for (Y, x, y)
// scaled to the zenith's values; below the horizon, the horizon's.
vec3 physicalSky(vec3 dir) {
    float cosTheta = max(dir.z, 0.01);
    float cosGamma = clamp(dot(dir, frame.sunDirection.xyz), -1.0, 1.0);
    float gamma = acos(cosGamma);
    vec3 f = (1.0 + frame.skyPerez[0].xyz * exp(frame.skyPerez[1].xyz / cosTheta)) *
             (1.0 + frame.skyPerez[2].xyz * exp(frame.skyPerez[3].xyz * gamma) +
              frame.skyPerez[4].xyz * (cosGamma * cosGamma));
    vec3 v = frame.skyZenithOverF0.xyz * f; // (Y, x, y)
    // world/sky.h daylightChromaticity: y raised onto the daylight locus (no purple horizon).
    return xyYToLinearRgb(v.y, max(v.z, (-3.0 * v.y + 2.87) * v.y - 0.275), v.x);
}

// Hemisphere sky light arriving along unit direction `dir` (z up), shared by the sky and the aerial perspective:
// the physical model or the scene's horizon-to-zenith gradient (FrameConstants::skyParams.x); below the horizon it
// darkens into the ground's bounce light.
vec3 skyRadiance(vec3 dir) {
    float up = clamp(dir.z, -1.0, 1.0);
    vec3 horizon = frame.skyHorizon.rgb;
    if (frame.skyParams.x == kSkyPhysical) {
        horizon = physicalSky(normalize(vec3(dir.xy, max(up, 0.0) + 1e-6)));
        if (up >= 0.0) return horizon;
    }
    if (up < 0.0) return mix(horizon, frame.groundAmbient.rgb, min(-up * 4.0, 1.0));
    return mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, sqrt(up));
}

// Irradiance-like ambient term for a surface with unit normal n: sky from above (its cosine-weighted mean radiance,
// computed on the CPU from the sky model), bounce light from below.
vec3 ambientLight(vec3 n) {
    return mix(frame.groundAmbient.rgb, frame.skyAmbient.rgb, 0.5 + 0.5 * n.z);
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

#include "atmosphere.glsl"

#endif
