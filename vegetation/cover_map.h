// Cover map: what the vegetation looks like from afar, per grass-map texel — the ground's colour beyond the far
// LOD limit, so the meadow does not end in a bare band where the plants stop being drawn (issue 15, "far band").
//
// Each category's appearance comes from its atlas row: the alpha-weighted mean linear colour of its cells, and the
// opaque fraction of a cell. Seen from the side, a plant shows about its billboard's opaque area (height^2 * aspect
// * opaque fraction); per m^2 of ground the categories' densities times those areas add up to S, the map's alpha.
// The texel's colour is the categories' colours weighted by their areas. How much of the ground S hides depends on
// the view's elevation angle, so terrain.frag turns S into a fraction per pixel.
#pragma once

#include "vegetation/atlas.h"
#include "vegetation/grass_map.h"
#include "vegetation/vegetation_params.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

struct CategoryLook {
    glm::vec3 colour{0.0f}; // alpha-weighted mean linear albedo of the category's atlas row
    double area = 0.0;      // opaque billboard area of an average plant, m^2
};

// One per vegetation category. Requires the atlas to have a row per category.
std::vector<CategoryLook> categoryLooks(const Atlas& atlas, const VegetationParams& params);

struct CoverMap {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> texels; // rgb linear albedo of the cover, a = S (m^2 of plant per m^2); top row north
    // Ground material weights, texel for texel of `texels`: component c the grass-map value of category c (the mean
    // over the texel's block, the sum of its channels, at most 1), which blends the category's ground_material
    // into the bare ground. Empty when no category has a ground material of its own.
    std::vector<glm::vec4> groundWeights;
    glm::vec2 origin{0.0f}; // world xy of the vegetation tile's south-west corner, which the map covers
    float size = 0.0f;      // tile edge, metres
};

// Largest cover map edge: a finer grass map is averaged in square blocks (about 0.25 m a texel on a 500 m tile).
inline constexpr uint32_t kMaxCoverMapEdge = 2048;

// The cover of the map's tile (origin and size from params), texel for texel of the grass map up to
// kMaxCoverMapEdge per edge; beyond, each texel covers f x f grass-map texels (f the least that fits; the blocks of
// the last row and column are clipped to the map). The ground material weights are averaged in the same blocks.
CoverMap makeCoverMap(const GrassMap& map, const Atlas& atlas, const VegetationParams& params);
// The same from the categories' looks (a world computes them once for all its tiles).
CoverMap makeCoverMap(const GrassMap& map, std::span<const CategoryLook> looks, const VegetationParams& params);

} // namespace sward
