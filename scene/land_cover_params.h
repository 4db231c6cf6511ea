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

} // namespace sward
