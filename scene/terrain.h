// The scene's ground: built from "terrain" (procedural heightfield, heightmap raster or glTF mesh), and the
// vegetation tile fitted to it.
#pragma once

#include "vegetation/vegetation_params.h"
#include "world/ground.h"

namespace sward {

struct Scene;

// Builds the scene's ground: the procedural heightfield, or loads its heightmap / mesh (a world's DEM: the window of
// its tile (0, 0) only). Errors name the scene file
// and the terrain key: a missing or unreadable file, and a ground whose selected materials and slope limit leave
// no surface for plants.
Ground buildTerrain(const Scene& scene);

// The vegetation parameters on this ground: a heightmap or mesh ground sets the tile's world origin to its
// south-west corner and its size to its larger side rounded up to whole fields, unless the scene sets
// vegetation.world_origin / tile_size (a world's DEM: the scene's own, fitted by fitWorldToDem).
VegetationParams vegetationOn(const Scene& scene, const Ground& terrain);

} // namespace sward
