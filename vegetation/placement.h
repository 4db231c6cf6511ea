// Reproducible placement of ground vegetation (paper section 3.1-3.2, issue 4).
//
// Every plant is a pure function of (seed, tile, field, cluster, category, sample) through counter-based hashing,
// so any field can be regenerated alone, in any order, on any number of threads, with bitwise identical records.
// Per cluster and category: the grass-map density is integrated over an 8x8 grid of sub-cells; the expected
// count is rounded by a hashed threshold (unbiased, deterministic); the plants are a stratified jittered point set
// (rows of equal-area strata, so no clumps or holes) warped through the density's inverse CDF so that they follow
// the map inside the cluster too. Positions are quantised first and the ground is evaluated at the *decoded*
// position, so a decoded plant lies exactly on the ground. Only + - * / floor sqrt are used, never libm
// transcendentals, and the library is built with -ffp-contract=off: results match on every x86-64 machine.
#pragma once

#include "vegetation/grass_map.h"
#include "world/ground.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"

#include <cstdint>
#include <string>

namespace sward {

// Sub-cells per cluster edge over which the density is integrated and warped.
inline constexpr uint32_t kDensityGrid = 8;

// Expected plant count of a tile: the integral of the map's bilinear densities (exact; clipping by the ground's
// extent is not taken into account).
double predictPlantCount(const GrassMap& map, const VegetationParams& params);

// Throws sward::Error naming the grass map if the predicted plant records (static + dynamic) and the tile's cluster
// records exceed the memory budget or the machine's physical memory, or the predicted plants exceed the plant
// instance ids (checkPlantIdSpace). Called by generateTile before anything is allocated.
void checkMemoryBudget(const GrassMap& map, const VegetationParams& params);

// The plants of one tile get the ground-truth instance ids 1 .. gpu::kMaxPlantInstances (plant index + 1); more
// would wrap into the semantic class bits and into the objects' ids. Throws sward::Error
// "<what> <plants> plants, over the limit of ..." naming the keys that lower the count.
void checkPlantIdSpace(uint64_t plants, const std::string& what);

// Generates one field alone. Requires valid params (validateVegetationParams) and coord < fieldsPerTile; throws
// sward::Error if this field alone exceeds the memory budget. Plants where the ground has no surface, or one
// its GroundSelection keeps bare, are dropped.
FieldVegetation generateField(const Ground& ground, const GrassMap& map, const VegetationParams& params, TileCoord tile,
                              FieldCoord coord);

// Generates every field of a tile on `threads` threads (0 = hardware concurrency). The result does not depend on
// the thread count. Checks the memory budget and the predicted plant count first, the placed plant count against
// the plant instance ids after placement (a prediction just below the limit may round above it), and assigns the
// fields' buffer ranges in field order.
VegetationTile generateTile(const Ground& ground, const GrassMap& map, const VegetationParams& params, TileCoord tile,
                            uint32_t threads);

} // namespace sward
