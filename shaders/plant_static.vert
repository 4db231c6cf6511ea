#version 460
#extension GL_GOOGLE_include_directive : require
// Draws pre-baked plant vertices (benchmark baseline): same outputs as plant.vert, no per-frame expansion.
#include "shared/frame.glsl"
#include "shared/vegetation.glsl"

layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Baked { BakedVertex baked[]; };
// Unused here, declared so the pipeline layout matches plant.vert's.
layout(set = 0, binding = kBindingAtlasCells, std430) readonly buffer Cells { AtlasCellGpu cells[]; };

layout(location = 0) out vec2 outUv;
layout(location = 1) out vec3 outWorld;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec3 outUp;
layout(location = 4) flat out uint outFade;
layout(location = 5) out float outHeightFraction;
layout(location = 6) flat out float outRandom;

void main() {
    BakedVertex v = baked[gl_VertexIndex];
    outUv = v.uvRandom.xy;
    outWorld = v.positionFraction.xyz;
    outViewDepth = (frame.view * vec4(v.positionFraction.xyz, 1.0)).z;
    outUp = octahedralDecode(v.upFade.x);
    outFade = v.upFade.y;
    outHeightFraction = v.positionFraction.w;
    outRandom = v.uvRandom.z;
    gl_Position = frame.viewProj * vec4(v.positionFraction.xyz, 1.0);
}
