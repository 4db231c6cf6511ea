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

// The drawn ground's vertex attributes at world `xy` (clamped into the ground): the smooth normal, material colour
// and texture coordinate interpolated over the triangle of `mesh` (groundDrawMesh(ground)) under xy, as the
// rasteriser interpolates them, and the height ground.height(xy). What a rut patch (render/track_renderer.h) is
// drawn with where the ground is unpressed, so it matches the ground around it.
gpu::TerrainVertex groundVertexAt(const Ground& ground, const GroundDrawMesh& mesh, glm::vec2 xy);

// A mesh ground's base-colour textures as one array image: every texture resampled (bilinear, in linear light)
// to size x size texels, sRGB RGBA8, with a box-filtered mip chain. Without textures: one white 1x1 layer, so
// the binding is always valid.
struct GroundTextureArray {
    uint32_t size = 1, layers = 1, mipLevels = 1;
    std::vector<std::vector<uint8_t>> levels; // per mip level: every layer's texels, layer after layer
};

// Largest edge of a ground texture layer: textures are scaled to the next power of two of the largest one, at most
// this (GPU memory: 4 MiB per layer at 1024, plus a third for the mips).
inline constexpr uint32_t kMaxGroundTextureLayerSize = 1024;

GroundTextureArray groundTextureArray(const Ground& ground);

} // namespace sward
