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

// A world's `grass_map` (issue 51): the image stretched over the world's tiles, north up, whole pixels per tile (the
// rule of a land cover without georeferencing, landCoverGrid), each tile's map its pixels (no blur: windows of the
// image are the image). Loads and checks it: the largest intensity of each channel as a 1 x 1 map (the budget's
// bound) and its pixels per tile. Throws sward::Error naming the scene, 'grass_map' and the file.
GrassMap worldGrassMapBound(const Scene& scene, glm::uvec2& pixelsPerTile);
// The grass map's pixels over the world tile whose south-west corner is `origin`.
GrassMap worldGrassMapWindow(const Scene& scene, glm::dvec2 origin);

// The land cover's grass map over the world tile whose south-west corner is `origin` (loadLandCoverTileGrassMap).
GrassMap worldLandCoverGrassMap(const Scene& scene, glm::dvec2 origin, uint32_t threads = 0);

} // namespace sward
