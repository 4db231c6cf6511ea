// Cut-out polygons of atlas cells: a convex polygon of at most n corners (4 <= n <= gpu::kMaxCutoutCorners) per cell
// that holds every
// texel the plant shaders' alpha test can keep, so the near and mid quads are drawn as that polygon (a fan of
// triangles) and the cell's transparent margins are never rasterised (issue 17: fragment work).
//
// Conservative by construction: the polygon contains, for every mip level 0..maxLevel, the footprint of every texel
// with alpha > 0 grown by gpu::kCutoutMarginTexels texels of that level (bilinear filtering reaches one texel; alpha-to-
// coverage with a sharpened alpha can keep a fragment next to an opaque one, one pixel ~ one texel of the sampled
// level further). Levels coarser than maxLevel are not covered: a quad seen at such a level (far away or edge-on)
// may lose a few pixels to the cut, which is why the cut-out is a switch (VegetationRenderer::setCutout).
#pragma once

#include "vegetation/atlas.h"

#include "shared/gpu_layout.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace sward {

// Corners in cell coordinates (u right, v down, 0..1: the cell's uv rectangle), counter-clockwise in (u, v), padded
// to gpu::kMaxCutoutCorners by repeating the last corner (the fan's extra triangles are empty).
struct CutoutPolygon {
    std::array<glm::vec2, gpu::kMaxCutoutCorners> corners{};
    uint32_t count = 0; // distinct corners, 3..kMaxCutoutCorners

    // Whether point p (cell coordinates) lies inside or on the polygon.
    bool contains(glm::vec2 p) const;
    // Area as a fraction of the cell.
    float area() const;
};

// The whole cell (4 corners): cells with nothing to cut, and cut plants (they show a stretched lower part).
CutoutPolygon fullCellPolygon();

// One polygon of at most `corners` corners (4..kMaxCutoutCorners: a cell that needs more keeps the whole cell) per
// cell, indexed row * desc.maxColumns() + column (cells right of a short row: the whole cell). Fewer corners mean
// fewer triangles and shorter shared edges, more corners a tighter fit. Needs the mip chain (buildMipChain) up to
// maxLevel; maxLevel is clamped to the levels present.
std::vector<CutoutPolygon> atlasCutouts(const Atlas& atlas, uint32_t corners = gpu::kMaxCutoutCorners,
                                        uint32_t maxLevel = gpu::kCutoutMaxLevel);

} // namespace sward
