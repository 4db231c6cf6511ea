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
    uint32_t cascades = 3;        // wanted number of shells (fewer when firstDistance reaches lastDistance)
    double firstDistance = 60.0;  // far end of the first, finest shell (scene render.shadow_distance)
    double lastDistance = 154.0;  // far end of the last shell: where shadows have faded out
    uint32_t mapSize = 2048;      // texels per edge of each cascade's map
    double casterMargin = 4.0;    // metres a shadow caster may lie outside the frustum (plants, the right view)
    double heightRange = 0.0;     // the ground's highest minus lowest point (depth range of the maps)
};

struct ShadowCascade {
    glm::dmat4 viewProj{1.0}; // world -> the cascade's clip space: orthographic, reversed Z (1 nearest the sun)
    double begin = 0.0;       // receivers at distances [begin, end] from the camera use this cascade
    double end = 0.0;
    double radius = 0.0;      // half the map's edge, metres (texel = 2 radius / mapSize)
    double depthBias = 0.0;   // max(5 cm, 1.5 texels) along the light ray, in the cascade's depth units
};

// Shell ends: firstDistance, then geometric up to lastDistance; one shell when firstDistance >= lastDistance.
std::vector<double> shadowSplits(const ShadowCascadeParams& params);

// The cascades of `camera` for a sun in direction `toSun` (unit, towards the sun). Each map covers a sphere around
// its shell of the frustum, widened by casterMargin, whose radius depends only on the intrinsics and the shell (so
// a texel keeps its size as the camera turns) and whose centre is snapped to whole texels in light space (so
// shadows do not shimmer as the camera moves).
std::vector<ShadowCascade> fitShadowCascades(const Camera& camera, const glm::dvec3& toSun,
                                             const ShadowCascadeParams& params);

} // namespace sward
