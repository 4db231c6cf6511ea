// CPU reference of the GPU vegetation expansion (shaders/vegetation_expand.comp, shared/vegetation.glsl,
// shared/plant_vertex.glsl): the same math in C++, in the same order, for tests that check the GPU result and for
// the range sensors (range/), which cast rays against the plants the cameras see. Not used for rendering. Float arithmetic mirrors the shaders; results agree to rounding (FMA contraction
// and transcendental precision may differ on a GPU), which the tests allow for.
#pragma once

#include "vegetation/atlas_cutout.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"
#include "world/camera.h"

#include "shared/gpu_layout.h"

#include <array>
#include <vector>

namespace sward {

struct ReferenceExpansion {
    std::array<std::vector<gpu::ExpandedPlant>, gpu::kLodCount>
        lods; // each in frontToBack cluster order, then plant order
    uint32_t visibleClusters = 0;
    uint64_t plantsConsidered = 0; // plants of visible clusters
};

// Expands every plant of `tile` for `camera` at simulation time `time`, with the scene's LOD, wind and
// category heights; far slicing and merging use the atlas's `ExpansionAtlas` figures and the camera's fy.
struct ExpansionAtlas {
    std::array<float, 4> card;   // cardCover() of the atlas drawn
    std::array<float, 4> aspect; // meanAspects() of its description
};
ReferenceExpansion referenceExpand(const VegetationTile& tile, const VegetationParams& vegetation, const LodParams& lod,
                                   const WindParams& wind, const Camera& camera, double time,
                                   const ExpansionAtlas& atlas);

// Plant `i` of `field` with dynamic record `dynamic` expanded whole at simulation time `time`: position, height after
// size and cut, wind + bend tip, state; no LOD fade, merging (width scale 1) or slicing. referenceExpand's instances
// are this (with the field's own dynamic record) plus those.
gpu::ExpandedPlant expandWholePlant(const VegetationParams& vegetation, const WindParams& wind,
                                    const FieldVegetation& field, uint32_t i, const gpu::PlantDynamic& dynamic,
                                    double time);

// The plant's random value in [0, 1] (plant_vertex.glsl: PlantQuad::random, attributes bits 16-23): above a half, its
// cards are mirrored.
float plantRandom(const gpu::ExpandedPlant& plant);

// The corners of each quad of `plant` drawn at `lod` (whole quads, no slicing), four per quad in the order (x across,
// y up) (0, 0), (1, 0), (1, 1), (0, 1): the quad's triangles are corners 0, 1, 2 and 0, 2, 3, as kFullQuadFan and
// fanCorner draw them. `corners` holds 4 * quads entries (16 for the near LOD).
void plantQuadCorners(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cameraPosition, glm::vec3 cellBaseAspect,
                      glm::vec3* corners);

// plantQuadCorners in two steps, for plants whose quads' frames do not depend on their tip (all but felled ones, and
// not for far billboards, which face the camera): unbentQuadCorners gives each corner before its bend and its bend
// weight (the height fraction squared), bentPoint bends it by a tip; together bitwise plantQuadCorners' corners.
void unbentQuadCorners(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cellBaseAspect, glm::vec3* corners,
                       float* bends);
glm::vec3 bentPoint(glm::vec3 unbent, float bend, glm::vec2 tip, float height, glm::vec3 up);

// The gpu::plantVertexCount(lod, cutoutCorners) vertex positions of one expanded plant (plant_vertex.glsl), for an
// atlas cell with base (baseU, baseV) and width / height `aspect`; with `cutout` and cutoutCorners (4..8), near and
// mid quads as fans over that cut-out polygon of the cell (atlasCutouts(atlas, cutoutCorners); cut plants: the whole
// quad).
std::vector<glm::vec3> referencePlantVertices(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cameraPosition,
                                              glm::vec3 cellBaseAspect, const CutoutPolygon* cutout = nullptr,
                                              uint32_t cutoutCorners = 0);

// The near blades of `plant` (lod.near_blades = `blades`; shaders/shared/plant_blades.h, the same text as the
// shaders'), as the blade draw's triangles: gpu::kBladeIndices vertices per blade in bladeIndex order, for an atlas
// cell of width / height `aspect`.
std::vector<glm::vec3> referenceBladeVertices(const gpu::ExpandedPlant& plant, uint32_t blades, float aspect);

} // namespace sward
