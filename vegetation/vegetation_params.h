// Vegetation configuration: densities, sizes and atlas layout per category, the grass-map channel mapping,
// the tile/field/cluster structure and the memory budget. parseVegetationParams() reads it from a scene file.
//
// JSON keys (all optional; defaults in brackets; docs/scene-format.md has the full table):
//   seed                [1]      unsigned; every plant is a pure function of (seed, tile, field, cluster, sample)
//   tile_size           [500]    metres; a whole number of fields
//   field_size          [25]     metres, 1..256; a whole number of clusters; positions quantise to field_size/65536
//   cluster_size        [5]      metres, >= 0.5
//   world_origin        [[0,0]]  metres, world xy of tile (0, 0)'s min corner; tile (i, j) starts at origin + size*(i, j)
//   density_multiplier  [1]      global factor on every category density, 0..100
//   up_normal_blend     [0.5]    0 = plants grow along world +z, 1 = along the surface normal
//   memory_budget_mib   [1024]   limit on predicted plant record memory per tile (static + dynamic), MiB
//   categories          [ferns, grass, flowers]  1..4 objects, index = atlas row; keys not given in an entry
//                                default to the built-in category with the same index:
//     name              string   for messages and the channel mapping
//     density           plants per m^2 at full map intensity, 0..1000  [ferns 1.5, grass 16, flowers 1]
//     height            base plant height in metres, 0.01..20          [0.6, 0.35, 0.45]
//     height_variation  relative +- spread of the height, 0..0.95       [0.3, 0.35, 0.4]
//     variants          atlas columns, 1..64                            [4, 8, 8]
//     ground_material   the bare ground's preset where the category grows, as terrain.material  [none: the
//                       terrain's]
//   channels            [{"r": 0, "g": 1, "b": 2, "a": null}]  grass-map channel -> category index or name;
//                                null = unused
//   pattern             [all strengths 0: the map alone]  field-scale structure (meadow_pattern.h):
//     patch_size        metres, 1..200                                  [8]
//     patchiness        density contrast between patches, 0..1          [0]
//     height_gradient   relative height change between patches, 0..0.9 [0]
//     clumping          pull toward tussock centres, 0..0.9             [0]
//     clump_size        tussock spacing in metres, 0.05..5              [0.5]
#pragma once

#include "shared/plant_layout.h"
#include "vegetation/meadow_pattern.h"

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace sward {

// Level-of-detail distances (paper Figure 3), metres from the camera to the plant base.
struct LodParams {
    float nearToMid = 12.0f; // closer: 4 quads
    float midToFar = 40.0f;  // closer: 2 crossed quads; farther: 1 billboard
    float farLimit = 150.0f; // plants beyond are not drawn (the terrain colour stands in)
    float band = 4.0f;       // width of the dithered cross-fade around each distance
    // Far billboards are drawn only above the height where a grazing ray has crossed this many layers of opaque card
    // (gpu::sliceHeight): their hidden lower parts cost nothing, and a ray reaches the ground through the drawn parts
    // with probability exp(-sliceLayers). 0: off.
    float sliceLayers = 8.0f;
    // Far billboards narrower on screen than this many pixels are merged into fewer, wider ones
    // (gpu::mergeWidthScale), each showing as many copies of its plant side by side: the same expected coverage
    // from fewer triangles. 0: off.
    float mergeWidth = 12.0f;
    // Far billboards shorter on screen than this many pixels are merged in depth (gpu::depthMergeHash, kDepthMerge-
    // Exponent): fewer, denser cards, so a grazing ray meets the same coverage through fewer layers. 0: off.
    float depthMerge = 16.0f;
    // Near plants of the grass categories drawn as this many opaque blades each (shaders/shared/plant_blades.h)
    // instead of their four alpha-tested cards: a CPU driver tests depth before shading opaque geometry, so a view
    // through dense grass shades about one layer instead of every card. 0: cards.
    uint32_t nearBlades = 0;
};

// Procedural wind (a pure function of simulation time; see shaders/shared/vegetation.glsl).
struct WindParams {
    double directionDegrees = 60.0; // direction the wind blows towards, clockwise from north (+y)
    float strength = 0.12f;         // steady lean: tip offset in plant heights
    float gustStrength = 0.18f;     // extra tip offset at gust peaks
    float gustFrequency = 0.25f;    // gust waves per second
    float gustWavelength = 30.0f;   // metres between gust fronts
    float flutter = 0.03f;          // fast cross-wind flutter, plant heights
    glm::vec2 direction() const;    // unit xy
};

struct VegetationCategory {
    std::string name;
    float density = 16.0f;         // plants per m^2 where the category's map channel is 1
    float height = 0.35f;          // base height in metres (the size byte scales it per plant)
    float heightVariation = 0.35f; // plant height = height * (1 + heightVariation * r), r uniform in [-1, 1]
    uint32_t variants = 8;         // atlas columns to pick from uniformly
    // The bare ground's preset where this category grows (ground_material): soil, dry_soil, mud, gravel,
    // forest_floor as 0..4 (the order of terrain.material and gpu::kGroundMaterial*; the GPU layer maps them), or
    // kNoGroundMaterial: the terrain's own.
    int32_t groundMaterial = -1;
};

inline constexpr int32_t kNoGroundMaterial = -1;

// Built-in defaults of category index i (0 ferns / forest floor, 1 grass, 2 shrubs and flowers, 3 "extra").
VegetationCategory defaultVegetationCategory(uint32_t index);

inline constexpr int32_t kUnusedChannel = -1;
// Fields per tile side and clusters per field side at most (validateVegetationParams): bounds of the tile's arrays.
inline constexpr uint32_t kMaxFieldsPerTileSide = 1024;
inline constexpr uint32_t kMaxClustersPerFieldSide = 64;

struct VegetationParams {
    uint64_t seed = 1;
    float tileSize = 500.0f;
    float fieldSize = 25.0f;
    float clusterSize = 5.0f;
    glm::vec2 worldOrigin{0.0f};
    float densityMultiplier = 1.0f;
    float upNormalBlend = 0.5f;
    uint64_t memoryBudgetBytes = uint64_t(1024) << 20;
    uint32_t categoryCount = 3;
    std::array<VegetationCategory, gpu::kMaxPlantCategories> categories = {
        defaultVegetationCategory(0), defaultVegetationCategory(1), defaultVegetationCategory(2),
        defaultVegetationCategory(3)};
    // channelCategory[c]: category fed by grass-map channel c (R, G, B, A), or kUnusedChannel.
    std::array<int32_t, 4> channelCategory = {0, 1, 2, kUnusedChannel};
    MeadowPattern pattern; // patches, height gradients and tussocks over the map's densities

    uint32_t fieldsPerTile() const;    // per side
    uint32_t clustersPerField() const; // per side
};

// Throws sward::Error (message names sourceName and the key, as 'vegetation.<key>') unless params is consistent:
// sizes positive and nested in whole numbers, densities/heights finite and in range, channel mapping pointing at
// existing categories.
void validateVegetationParams(const VegetationParams& params, const std::string& sourceName);

// Reads the keys documented above from the scene file's "vegetation" object (null: the defaults); unknown keys are
// errors so that typos do not pass silently. Errors name the file and the JSON path, e.g.
// "meadow.json: 'vegetation.categories[0].density' must be between 0 and 1000 (got -1)".
VegetationParams parseVegetationParams(const nlohmann::json& json, const std::string& sourceName);

} // namespace sward
