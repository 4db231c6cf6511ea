// The plants as range sensors see them: each plant's near-LOD quads at one tick (vegetation/expansion_reference.h,
// the same math as the GPU expansion), or with lod.near_blades a grass plant's blades, the atlas's alpha at a hit,
// and the boxes Embree builds its BVHs from.
#pragma once

#include "vegetation/atlas.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"

#include "shared/gpu_layout.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace sward {

// One plant's near quads at one tick: its eight triangles (quad q's corners (0,0), (1,0), (1,1), (0,1) as triangles
// (0,1,2) = 2q and (0,2,3) = 2q + 1), each as its first corner p0 and edges e1 = p1 - p0, e2 = p2 - p0, stored
// component by component so that the eight ray tests run side by side (SIMD).
struct PlantQuads {
    static constexpr uint32_t kTriangles = 2 * gpu::kQuadsNear;
    float p0[3][kTriangles], e1[3][kTriangles], e2[3][kTriangles];
    glm::vec3 lo, hi;         // their bounding box
    uint32_t cell = 0;        // atlas cell (category * maxColumns + variant)
    float cutFraction = 1.0f; // the part of the cell shown (cut plants show their lower part)
    uint32_t label = 0;       // (semantic class << kInstanceBits) | plant index in the tile + 1
    bool mirrored = false, present = false;
    // lod.near_blades: the plant's opaque blade triangles, three corners each (referenceBladeVertices), instead of
    // its quads.
    std::vector<glm::vec3> blades;
};

// The atlas's level-0 alpha and cell table.
struct AtlasAlpha {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> alpha;
    std::vector<glm::vec4> uvRects;     // per cell
    std::vector<glm::vec3> baseAspects; // per cell: base u, base v, aspect
    uint32_t maxColumns = 1;
    std::array<uint32_t, 4> columns{};

    explicit AtlasAlpha(const Atlas& atlas);
    // Bilinear alpha at uv, clamp to edge, texel centres at +0.5 (the GPU sampler's rule at level 0).
    float sample(glm::vec2 uv) const;
    // sample(uv) >= 0.5, the alpha test; decided by one lookup where the four texels around uv are all opaque or all
    // transparent (a bilinear mix of values on one side of 0.5 stays there), else by sample().
    bool opaque(glm::vec2 uv) const;
    // plant_vertex.glsl's cell of a plant's attributes.
    uint32_t cellOf(uint32_t attributes) const;

private:
    std::vector<uint8_t>
        between_; // per 2 x 2 texel neighbourhood, (width + 1) x (height + 1): 0 all < 0.5, 2 all >= 0.5, 1 mixed
};

// A resting plant's quad corners before their bend and their bend weights (unbentQuadCorners), which stay the same
// from tick to tick: only the wind's tip moves it.
struct UnbentPlant {
    glm::vec3 corners[4 * gpu::kQuadsNear];
    float bends[4 * gpu::kQuadsNear];
};
UnbentPlant unbentPlant(const AtlasAlpha& atlas, const VegetationParams& vegetation, const FieldVegetation& field,
                        uint32_t i);

// Plant `i` of `field` (tile index `plantInTile`) with dynamic record `dynamic` at simulation time `time`; `unbent`,
// for a plant in its resting geometry, saves recomputing its quads' frames (the result is bitwise the same).
// `blades` > 0: the plant is drawn as that many blades (bladesOf), and so seen.
PlantQuads plantQuads(const AtlasAlpha& atlas, const VegetationParams& vegetation, const WindParams& wind,
                      const FieldVegetation& field, uint32_t i, uint32_t plantInTile, const gpu::PlantDynamic& dynamic,
                      double time, const UnbentPlant* unbent = nullptr, uint32_t blades = 0);

// The blades of a plant of category `category` with lod.near_blades = `nearBlades`: that many for a category the atlas
// paints as grass (as the renderer draws them), else 0.
uint32_t bladesOf(const VegetationParams& vegetation, uint32_t nearBlades, uint32_t category);

// True when a dynamic record leaves the plant's geometry as at rest: no bend, standing, uncut (its spring's velocity
// aside), so only the wind moves it.
bool restingGeometry(const gpu::PlantDynamic& dynamic);

// The horizontal tip offsets (plant heights, world xy) the scene's wind gives a resting plant at any time and place:
// their bounding box and largest length.
struct WindTipRange {
    glm::vec2 lo, hi;
    float length;
};
WindTipRange windTipRange(const WindParams& wind);

// The box plant `i` of `field` occupies at rest under any tip offset of `wind`: its quads without wind, shifted by
// the tip's reach and lowered by its drop.
// `blades` > 0: of the plant's blades (bladesOf) instead of its quads.
void restingBounds(const AtlasAlpha& atlas, const VegetationParams& vegetation, const FieldVegetation& field,
                   uint32_t i, const UnbentPlant& unbent, const WindTipRange& wind, glm::vec3& lo, glm::vec3& hi,
                   uint32_t blades = 0);

// The nearest opaque hit of the ray o + t d (t in [tNear, best)) on the plant's eight triangles: updates `best` and
// `normal` (unnormalised, the triangle's) and returns true when there is one.
bool intersectPlant(const PlantQuads& plant, const AtlasAlpha& atlas, glm::vec3 o, glm::vec3 d, float tNear,
                    float& best, glm::vec3& normal);

} // namespace sward
