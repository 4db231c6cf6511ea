#ifndef SWARD_GROUND_TRUTH_FRAGMENT_GLSL
#define SWARD_GROUND_TRUTH_FRAGMENT_GLSL
// Terrain ground truth (1 sample per pixel): the planar depth of the surface at the pixel centre, stored as
// float bits in an R32_UINT attachment, the label (semantic class "track" where a rut is pressed at least
// kTrackLabelDepth deep, "turf" where terrain.frag shades turf at least half at this point, else "ground"; no instance) and the
// triangle's normal (terrain_truth.vert, track.vert). truth_holes.frag leaves the blocks drawn as rut
// patches to them (render/track_renderer.h). Integer and 32-bit float attachments written without blending hold exactly what
// the shader computed.
#include "shared/frame.glsl"
#include "shared/ground_cover.glsl"
#include "shared/flow_fragment.glsl"
#include "shared/horizon_ring.glsl"
#ifdef SWARD_TERRAIN_HOLES
#include "shared/ground_tracks.glsl"
#endif

layout(location = 0) in vec3 inWorld;
layout(location = 2) in float inViewDepth;
layout(location = 5) flat in vec3 inNormal;
layout(location = 6) in float inRut;
layout(location = 0) out uint outDepthBits;
layout(location = 1) out uvec2 outLabel; // label, no tile (a plant's only)
layout(location = 2) out vec4 outNormal; // camera-frame unit normal, w 0

void main() {
#ifdef SWARD_TERRAIN_HOLES
    if (inTrackPatch(inWorld.xy)) discard;
#endif
    if (groundHiddenHere(inWorld.xy, tile.material.w)) discard;
    outDepthBits = floatBitsToUint(inViewDepth);
    // The horizon ring is the terrain's coarse surface, labelled ground: its cover is a look from afar, not turf.
    bool turf = tile.material.w != kGroundHorizonRing && turfAt(inWorld) >= 0.5;
    uint semantic = inRut >= kTrackLabelDepth ? kSemanticTrack : turf ? kSemanticTurf : kSemanticGround;
    outLabel = uvec2(semantic << kInstanceBits, 0u);
    outNormal = vec4(inNormal, 0.0);
    writeFlowFragment();
}

#endif
