// The scene's "land_cover" object (docs/scene-format.md): the grass map made from a land-cover raster through a table
// of class intensities (vegetation/land_cover.h), an alternative to "grass_map".
#pragma once

#include "common/json_reader.h"
#include "vegetation/land_cover.h"

namespace sward {

// Reads every key of the "land_cover" object but "file", which the scene resolves through its asset policy:
// "preset" ("esa_worldcover" or absent), "table" ({"<code>": [r, g, b] or [r, g, b, a]}, overriding or extending the
// preset), "border" (metres), "band" and "nodata" (the class code nodata pixels count as). The table must end up
// with at least one class and hold the nodata code. Errors name the file and the JSON path.
LandCoverParams parseLandCoverParams(JsonReader& r);

struct Scene;

// The world a scene's land cover covers: world.tiles tiles of vegetation.tile_size (issue 51).
LandCoverWorld landCoverWorld(const Scene& scene);

// A world's land cover from its raster's header (readRasterInfo: no pixels are read): the checks of landCoverGrid.
// Throws sward::Error naming the scene, 'land_cover' and the raster.
LandCoverGrid worldLandCoverGrid(const Scene& scene);

// The land cover point-sampled over the square of `side` metres whose south-west corner is `origin` (world xy), one
// texel per resolution x resolution cell (loadLandCoverPointGrassMap): a horizon ring's far cover.
GrassMap worldLandCoverPointMap(const Scene& scene, glm::dvec2 origin, double side, uint32_t resolution);

// The land cover's grass map over the world tile whose south-west corner is `origin` (loadLandCoverTileGrassMap).
GrassMap worldLandCoverGrassMap(const Scene& scene, glm::dvec2 origin, uint32_t threads = 0);

} // namespace sward
