#version 460
#extension GL_GOOGLE_include_directive : require
// Scene object shading: the material's base colour under the same light as the terrain (Lambert sun with
// shadow map + hemispherical ambient), so objects sit in the scene's lighting.
#include "shared/frame.glsl"
#include "shared/shadow.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inViewDepth;
layout(location = 3) in vec3 inBaseColor;

layout(location = 0) out vec4 outColor;

void main() {
    vec3 n = normalize(inNormal);
    float sun = max(dot(n, frame.sunDirection.xyz), 0.0) * sunShadow(inWorld);
    vec3 light = frame.sunRadiance.rgb * sun + ambientLight(n);
    outColor = vec4(inBaseColor * light, 1.0);
    outColor.rgb = aerialPerspective(outColor.rgb, inWorld);
}
