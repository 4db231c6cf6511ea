// Cascaded sun shadows (issue 18, "shadows without edges"): the view is cut into distance shells, each shadowed
// by its own orthographic map fitted around the part of the camera's frustum it covers. The last shell ends where
// the vegetation ends, so no surface that plants shade leaves the maps' reach, and shadows fade out over the last
// shell instead of stopping at an edge. Pure maths, the same on every machine: the render layer uploads the
// matrices, shaders/shared/shadow.glsl picks a cascade by the distance to the camera.
#pragma once

#include "world/camera.h"

#include <glm/glm.hpp>

#include <vector>

namespace sward {

struct ShadowCascadeParams {
    uint32_t cascades = 3;        // wanted number of shells (fewer where the distances below leave no room)
    double firstDistance = 60.0;  // far end of the first, finest shell at most (scene render.shadow_distance)
    double lastDistance = 154.0;  // far end of the last shell: where shadows have faded out
    double farPlantsFrom = 0.0;   // nearest far billboard (lod.mid - band / 2); 0: none, no alignment (shadowSplits)
    uint32_t mapSize = 2048;      // texels per edge of each cascade's map
    double casterMargin = 4.0;    // metres a shadow caster may lie outside the frustum (shadowCasterReach)
    double heightRange = 0.0;     // the ground's highest minus lowest point (depth range of the maps)
    double blend = 0.15;          // each cascade blends into the next over this last fraction of its shell
};

struct ShadowCascade {
    glm::dmat4 viewProj{1.0}; // world -> the cascade's clip space: orthographic, reversed Z (1 nearest the sun)
    double begin = 0.0;       // receivers at distances [begin, end] from the camera use this cascade first
    double end = 0.0;
    double firstReceiver = 0.0; // nearest receiver that samples it: begin, less the previous cascade's blend band
    double radius = 0.0;      // half the map's edge, metres (texel = 2 radius / mapSize)
    uint32_t mapSize = 0;     // texels per edge
    uint32_t mapOffset = 0;   // the map's first column in the row of all cascades' maps (shadowMapExtent)
    double depthBias = 0.0;   // max(5 cm, 1.5 texels) along the light ray, in the cascade's depth units
};

// How far from its base a plant may shade the ground when the sun's direction has z component `sunUp`: the
// shadow of its top (plants stand up to about 1.5 m) plus its own width and 2 m for the right view of a stereo
// pair; capped at 40 m for a sun at the horizon.
double shadowCasterReach(double sunUp);

// Shell ends. With far plants, the last shell alone holds them: it starts a caster's reach (and 1 m) before the
// first far billboard, and the shells before it run from min(firstDistance, that start) geometrically up to it, so
// each far billboard (nearly 90 % of the plants drawn) is drawn into one cascade only; without, the shells run
// from firstDistance geometrically to lastDistance. One cascade (or a first shell reaching the last): firstDistance.
std::vector<double> shadowSplits(const ShadowCascadeParams& params);

// Width and height of the row holding every cascade's map side by side.
glm::uvec2 shadowMapExtent(const ShadowCascadeParams& params);

// The cascades of `camera` for a sun in direction `toSun` (unit, towards the sun). Each map covers a sphere around
// its shell of the frustum, widened by casterMargin, whose radius depends only on the intrinsics and the shell (so
// a texel keeps its size as the camera turns) and whose centre is snapped to whole texels in light space (so
// shadows do not shimmer as the camera moves).
std::vector<ShadowCascade> fitShadowCascades(const Camera& camera, const glm::dvec3& toSun,
                                             const ShadowCascadeParams& params);

} // namespace sward
