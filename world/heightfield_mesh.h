// The heightfield as it is drawn: one vertex per sample, at origin + (i, j) * spacing and the sample's height, row by
// row, and each cell's two triangles split along the (i, j)-(i+1, j+1) diagonal, wound counter-clockwise seen from
// above: (p00, p10, p11) and (p00, p11, p01). The one triangulation the renderer draws (render/ground_mesh), the range
// sensors cast rays against (range/ray_scene) and Heightfield::height interpolates.
#pragma once

#include "world/heightfield.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sward {

// Vertex (i, j) of the drawn heightfield, world metres.
inline glm::vec3 heightfieldVertex(const Heightfield& h, uint32_t i, uint32_t j) {
    return glm::vec3(h.origin() + glm::vec2(float(i), float(j)) * h.spacing(), h.sample(i, j));
}

// The triangles' vertex indices, three per triangle, into vertices numbered j * columns + i.
std::vector<uint32_t> heightfieldTriangleIndices(const Heightfield& h);

} // namespace sward
