#version 460
#extension GL_GOOGLE_include_directive : require
// Plant quads from expanded instances: one indexed indirect draw per LOD (push constant lod), every pass indexing
// each quad's corners (gl_VertexIndex = quad * quadCornerCount + corner: plantIndex), so each corner is shaded once.
#include "shared/frame.glsl"
#include "shared/vegetation.glsl"
#include "shared/plant_vertex.glsl"
#include "shared/plant_blades.glsl"
#include "shared/plant_shading.glsl"
#include "shared/shadow.glsl"
#include "shared/flow_vertex.glsl"

layout(constant_id = 0) const uint PASS = kPassMain; // kPassMain, kPassTruth or kPassShadow
layout(push_constant) uniform Push { uint lod; } push;

layout(set = 0, binding = kBindingPlantInstances, std430) readonly buffer Instances { ExpandedPlant instances[]; };
layout(set = 0, binding = kBindingInstancePlants, std430) readonly buffer InstancePlants { uint instancePlants[]; };
#ifdef SWARD_FLOW // the plants' records, and their state at the previous and the next tick
layout(set = 0, binding = kBindingFlowStatics, std430) readonly buffer FlowStatics { PlantStatic flowStatics[]; };
layout(set = 0, binding = kBindingFlowDynamicsPrevious, std430) readonly buffer FlowPrevious {
    PlantDynamic flowDynamicsPrevious[];
};
layout(set = 0, binding = kBindingFlowDynamicsNext, std430) readonly buffer FlowNext { PlantDynamic flowDynamicsNext[]; };
#endif

layout(location = 0) out vec2 outUv;
layout(location = 2) out float outViewDepth;
layout(location = 3) out vec4 outShadow; // colour pass: plantShadowCoordinate
layout(location = 4) flat out uint outFade;
layout(location = 5) out float outHeightFraction;
layout(location = 6) flat out float outRandom;
layout(location = 7) flat out uint outLabel; // ground truth: (semantic class << 24) | instance id
layout(location = 8) flat out uint outTile;  // ground truth: the tile's label (VegetationConstants::tile)
layout(location = 9) flat out vec3 outNormal; // ground truth: the triangle's camera-frame normal (truthNormal)
layout(location = 10) flat out mat3 outAlbedo; // colour pass: plantShading (locations 10-15)
layout(location = 13) flat out vec3 outAlbedoOffset;
layout(location = 14) out vec2 outSunTerms;  // plantSunLight: varies across the card
layout(location = 15) flat out vec3 outAmbient;
layout(location = 20) flat out vec3 outSunColour; // plantSunLight (16-17: flow_vertex.glsl)
layout(location = 21) out vec4 outHaze;      // colour pass: hazeAt
layout(location = 18) flat out vec4 outUvRect; // the cell's atlas rectangle (outUv is in cell coordinates)
layout(location = 19) flat out vec2 outMerge; // far merging: PlantQuad::repeat (copies across), PlantQuad::opacity

void main() {
    ExpandedPlant instance = instances[gl_InstanceIndex];
    if (PASS == kPassShadow) {
        // Only the plants that can shade this cascade's shell (shadowParams.yz: its distances widened by the
        // casters' reach): the others land outside the clip volume, so their triangles are culled before
        // rasterisation and each plant costs raster work in one or two cascades, not in all.
        float d = distance(instance.positionHeight.xyz, frame.shadowOrigin.xyz);
        if (d < frame.shadowParams.y || d > frame.shadowParams.z) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            return;
        }
    }
    if (push.lod == kLodNear && drawnAsBlades(instance)) { // drawn as blades instead (plant_blade.vert)
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    uint cell;
    const uint perQuad = quadCornerCount(push.lod, veg.options.x);
    PlantQuad quad = plantQuad(instance, push.lod, uint(gl_VertexIndex) / perQuad, veg.cameraPosition.xyz, cell);
    PlantVertex v = quadCorner(instance, quad, cell, push.lod, uint(gl_VertexIndex) % perQuad);
    outUv = v.uv;
    outUvRect = quad.uvRect;
    outMerge = vec2(quad.repeat, quad.opacity);
    outViewDepth = (frame.view * vec4(v.position, 1.0)).z;
    outFade = instance.fade | (push.lod << 21); // bits 21-22: the LOD, for the viewer's LOD colours
    outHeightFraction = v.heightFraction;
    outRandom = v.random;
    if (PASS == kPassTruth) {
        uint state = bitfieldExtract(instance.fade, 17, 4);
        uint semantic = state == kPlantStateFelled ? kSemanticFelled
                      : state == kPlantStateCut    ? kSemanticCut
                                                   : kSemanticVegetation + bitfieldExtract(instance.attributes, 0, 2);
        outLabel = (semantic << kInstanceBits) | (instancePlants[gl_InstanceIndex] + 1u);
        outTile = veg.tile.x;
        // Corner c, 1 <= c <= n - 2, is the first vertex of the triangle (c, c + 1, 0) (fanCorner), whose flat outputs
        // the triangle takes: its normal comes from the three corners as every pass draws them, the drawn triangle's
        // own plane (bent cards are flat per triangle, not per plant). Corners 0 and n - 1 start no triangle; they
        // compute the normal of the two corners after them instead of branching, and it is never used.
        uint own = uint(gl_VertexIndex) % perQuad;
        uint last = own == 0u || own == perQuad - 1u ? (own + 2u) % perQuad : 0u;
        vec3 p0 = v.position;
        vec3 p1 = quadCorner(instance, quad, cell, push.lod, (own + 1u) % perQuad).position;
        vec3 p2 = quadCorner(instance, quad, cell, push.lod, last).position;
        outNormal = truthNormal(cross(p1 - p0, p2 - p0), p0);
#ifdef SWARD_FLOW
        // The same point of the same quad, with the plant's state and wind of the previous and the next tick.
        uint plant = instancePlants[gl_InstanceIndex];
        ExpandedPlant before = plantAtTick(instance, flowStatics[plant], flowDynamicsPrevious[plant], frame.flowTimes.x);
        ExpandedPlant after = plantAtTick(instance, flowStatics[plant], flowDynamicsNext[plant], frame.flowTimes.y);
        writeFlowVertex(plantCorner(before, push.lod, uint(gl_VertexIndex), frame.flowReferencePrevious.xyz).position,
                        plantCorner(after, push.lod, uint(gl_VertexIndex), frame.flowReferenceNext.xyz).position);
#endif
    }
    if (PASS == kPassMain) {
        uint plant = instancePlants[gl_InstanceIndex];
        vec3 up = octahedralDecode(instance.up);
        PlantShading shading = plantShading(instance.fade, push.lod, up, v.random, plantColourHash(plant));
        outAlbedo = shading.albedo;
        outAlbedoOffset = shading.albedoOffset;
        outAmbient = shading.ambient;
        // The corner's place across the plant for the rounded shading normal; far billboards, a few pixels wide,
        // stay flat (their gradient would only add edges between neighbours).
        vec3 toCamera = normalize(veg.cameraPosition.xyz - v.position);
        float across = clamp(dot(v.position - quad.base, quad.side) / max(0.5 * quad.width, 1e-6), -1.0, 1.0);
        PlantSunLight sun = plantSunLight(cross(quad.side, quad.rise), quad.side, push.lod == kLodFar ? 0.0 : across, up,
                                          toCamera);
        outSunColour = sun.colour;
        outSunTerms = sun.terms;
        outShadow = plantShadowCoordinate(v.position, instance.positionHeight.xyz, plantShadowHash(plant));
        outHaze = hazeAt(v.position);
    }
    if (PASS != kPassMain) {
        outShadow = vec4(0.0);
        outSunColour = vec3(0.0);
        outSunTerms = vec2(0.0);
        outHaze = vec4(0.0);
    }
    if (PASS != kPassTruth) {
        outLabel = 0u;
        outTile = 0u;
        outNormal = vec3(0.0);
    }
    gl_Position = (PASS == kPassShadow ? frame.shadowViewProj : frame.viewProj) * vec4(v.position, 1.0);
}
