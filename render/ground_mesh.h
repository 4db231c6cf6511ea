// The ground as the GPU draws it: one vertex and index list for colour, shadow and truth passes alike.
//
// A heightfield becomes its grid, split along each cell's (i,j)-(i+1,j+1) diagonal exactly as
// Heightfield::height() interpolates; a mesh ground keeps its triangles and vertex positions bit for bit, so a
// plant placed with Ground::surface() stands on the drawn surface.
#pragma once

#include "shared/gpu_layout.h"
#include "world/ground.h"

#include <cstdint>
#include <vector>

namespace sward {

struct GroundDrawMesh {
    std::vector<gpu::TerrainVertex> vertices;
    std::vector<uint32_t> indices; // triangle list
};

GroundDrawMesh groundDrawMesh(const Ground& ground);

} // namespace sward
