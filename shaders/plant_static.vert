#version 460
#extension GL_GOOGLE_include_directive : require
// Draws pre-baked plant vertices (benchmark baseline): same outputs as plant.vert, no per-frame expansion.
#include "shared/frame.glsl"
#include "shared/vegetation.glsl"
#include "shared/plant_shading.glsl"
#include "shared/shadow.glsl"

layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Baked { BakedVertex baked[]; };
// Unused here, declared so the pipeline layout matches plant.vert's.
layout(set = 0, binding = kBindingAtlasCells, std430) readonly buffer Cells { AtlasCellGpu cells[]; };

layout(location = 0) out vec2 outUv;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec4 outShadow;
layout(location = 4) flat out uint outFade;
layout(location = 5) out float outHeightFraction;
layout(location = 6) flat out float outRandom;
layout(location = 7) flat out uint outLabel; // ground truth only: plant_fragment.glsl declares it for every pass
layout(location = 10) flat out mat3 outAlbedo; // plantShading (locations 10-15)
layout(location = 13) flat out vec3 outAlbedoOffset;
layout(location = 14) out vec2 outSunTerms;
layout(location = 15) flat out vec3 outAmbient;
layout(location = 20) flat out vec3 outSunColour;
layout(location = 21) out vec4 outHaze;
layout(location = 18) flat out vec4 outUvRect; // baked coordinates are the atlas's own
layout(location = 19) flat out vec2 outMerge;

void main() {
    BakedVertex v = baked[gl_VertexIndex];
    outUv = v.uvRandom.xy;
    outUvRect = vec4(0.0, 0.0, 1.0, 1.0);
    outMerge = vec2(1.0);
    outViewDepth = (frame.view * vec4(v.positionFraction.xyz, 1.0)).z;
    // Baked vertices carry no LOD: the LOD overlay shows every plant as far.
    vec3 up = octahedralDecode(v.upFade.x);
    PlantShading shading = plantShading(v.upFade.y, kLodFar, up, v.uvRandom.z, v.uvRandom.z);
    outAlbedo = shading.albedo;
    outAlbedoOffset = shading.albedoOffset;
    outAmbient = shading.ambient;
    // Baked vertices keep no card: lit as a card facing up (the same instructions as plant.vert's).
    PlantSunLight sun = plantSunLight(up, vec3(0.0), 0.0, up, normalize(frame.cameraPosition.xyz - v.positionFraction.xyz));
    outSunColour = sun.colour;
    outSunTerms = sun.terms;
    outHaze = hazeAt(v.positionFraction.xyz);
    // Baked vertices keep no root: the cascade is chosen per vertex (a timing baseline; its images are not compared).
    outShadow = plantShadowCoordinate(v.positionFraction.xyz, v.positionFraction.xyz, v.uvRandom.z);
    outFade = v.upFade.y;
    outHeightFraction = v.positionFraction.w;
    outRandom = v.uvRandom.z;
    outLabel = 0u;
    gl_Position = frame.viewProj * vec4(v.positionFraction.xyz, 1.0);
}
