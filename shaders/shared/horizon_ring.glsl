#ifndef SWARD_HORIZON_RING_GLSL
#define SWARD_HORIZON_RING_GLSL
// A world's horizon ring (render/horizon_ring.h): the tiles' ground is drawn within the ground disc, world.view_distance
// (FrameConstants::coverBand.w) around the reference camera (shadowOrigin.xy), and a coarse heightfield of the whole
// world beyond it, each surface discarding its fragments on the other's side, so the two never overlap and a frame
// never depends on which tiles beyond the disc happen to be resident. Without a disc (coverBand.w 0) nothing changes.
// Requires frame.glsl.

// Whether a fragment of ground `kind` (kGroundTile / kGroundHorizonRing) at world xy lies on the other's side.
bool groundHiddenHere(vec2 world, uint kind) {
    float radius = frame.coverBand.w;
    if (radius <= 0.0) return false;
    bool inside = length(world - frame.shadowOrigin.xy) < radius;
    return inside == (kind == kGroundHorizonRing);
}

// A ground vertex as drawn. The ring's vertices within its rim width (normal.w, a coarse cell's diagonal) of the disc
// sink to its floor (uvLayer.w, the lowest height the world's ground can have): every ring triangle the disc's edge
// crosses lies there wholly, so at the seam the ring is never above the tiles' ground and a ray passing over their
// edge meets the ring (a step down, never a crack under the ring's edge where sky would show). Tiles' vertices have
// normal.w 0 and are drawn as they are.
vec3 groundVertexPosition(vec4 positionHeight, vec4 normal, vec4 uvLayer) {
    vec3 p = positionHeight.xyz;
    if (normal.w > 0.0 && length(p.xy - frame.shadowOrigin.xy) < frame.coverBand.w + normal.w) p.z = uvLayer.w;
    return p;
}

#endif
