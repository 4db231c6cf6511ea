// Sun shadow lookup (kBindingShadowMap of the shading passes): 4 hardware-PCF taps on a reversed-Z shadow map.
#ifndef SWARD_SHADOW_GLSL
#define SWARD_SHADOW_GLSL

#include "config.h"

layout(set = 0, binding = kBindingShadowMap) uniform sampler2DShadow shadowMap;

float sunShadow(vec3 world) {
    if (frame.shadowParams.x == 0.0) return 1.0;
    vec4 clip = frame.shadowViewProj * vec4(world, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    float reference = ndc.z + frame.shadowParams.y; // reversed Z: larger is closer to the sun
    float texel = frame.shadowParams.z;
    float lit = 0.0;
    lit += texture(shadowMap, vec3(uv + vec2(-0.5, -0.5) * texel, reference));
    lit += texture(shadowMap, vec3(uv + vec2(0.5, -0.5) * texel, reference));
    lit += texture(shadowMap, vec3(uv + vec2(-0.5, 0.5) * texel, reference));
    lit += texture(shadowMap, vec3(uv + vec2(0.5, 0.5) * texel, reference));
    return lit * 0.25;
}

#endif
