#version 460
// sward-view: tonemaps the resolved linear HDR image into the swapchain with exactly the curve of
// io/image_files.cpp toneMap (exposure, then Narkowicz's ACES fit on the luminance, the colour scaled by the same
// ratio and desaturated towards grey where a channel would clip), so the window shows what the PNG previews show.
// SRGB_TARGET: the swapchain format encodes sRGB itself; else it is encoded here.
#extension GL_GOOGLE_include_directive : require
#include "shared/config.h"

layout(constant_id = 0) const bool SRGB_TARGET = true;

layout(set = 0, binding = kPresentBindingImage) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } push;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

float filmicCurve(float x) {
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
    vec3 x = max(texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * push.exposure, vec3(0.0));
    float luminance = dot(x, vec3(0.2126, 0.7152, 0.0722));
    float mapped = filmicCurve(luminance);
    x = luminance > 1e-8 ? x * (mapped / luminance) : vec3(0.0);
    float peak = max(x.r, max(x.g, x.b));
    if (peak > 1.0) x = mapped + (x - mapped) * ((1.0 - mapped) / (peak - mapped));
    if (!SRGB_TARGET) x = mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, greaterThan(x, vec3(0.0031308)));
    outColor = vec4(x, 1.0);
}
