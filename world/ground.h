// Ground: the surface plants stand on, either a Heightfield or an arbitrary triangle mesh (e.g. from glTF).
//
// surface(xy) answers "where is the ground straight below/above xy and which way does it face" in O(1) for
// heightfields and O(triangles per grid cell) for meshes, which share a uniform xy grid built once. It evaluates
// the same triangles that are rendered (flat per-triangle normals), so a plant placed at surface(xy).height is
// exactly on the drawn ground.
#pragma once

#include "world/heightfield.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace sward {

struct SurfacePoint {
    float height;     // world z of the ground at the queried xy, metres
    glm::vec3 normal; // unit normal of the ground triangle there, pointing up (z > 0)
};

// Indexed triangle list in sward's world frame (metres, Z up).
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices; // 3 per triangle
};

class Ground {
public:
    Ground() = default;
    explicit Ground(Heightfield heightfield);
    // Requires at least one non-vertical triangle and every index < positions.size() (throws sward::Error).
    // cellSize 0 picks a grid cell of about two mean triangle edges.
    explicit Ground(TriangleMesh mesh, float cellSize = 0.0f);

    // The top-most ground surface at xy, or nothing where no ground covers xy (outside the heightfield or mesh).
    std::optional<SurfacePoint> surface(glm::vec2 xy) const;

    glm::vec2 boundsMin() const { return boundsMin_; } // xy extent covered
    glm::vec2 boundsMax() const { return boundsMax_; }
    const Heightfield* heightfield() const { return heightfield_ ? &*heightfield_ : nullptr; }
    const TriangleMesh* mesh() const { return heightfield_ ? nullptr : &mesh_; }

private:
    std::optional<SurfacePoint> meshSurface(glm::vec2 xy) const;

    std::optional<Heightfield> heightfield_;
    TriangleMesh mesh_;
    glm::vec2 boundsMin_{0.0f}, boundsMax_{0.0f};
    // Uniform grid over the mesh's xy bounds in CSR form: triangles of cell c are
    // cellTriangles_[cellStart_[c] .. cellStart_[c + 1]).
    float cellSize_ = 1.0f;
    uint32_t gridWidth_ = 0, gridHeight_ = 0;
    std::vector<uint32_t> cellStart_, cellTriangles_;
};

} // namespace sward
