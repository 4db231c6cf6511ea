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
#include <string>
#include <vector>

namespace sward {

struct SurfacePoint {
    float height;          // world z of the ground at the queried xy, metres
    glm::vec3 normal;      // unit normal of the ground triangle there, pointing up (z > 0)
    bool plantable = true; // vegetation may grow here (GroundSelection)
    uint32_t triangle = 0; // a mesh ground: the index of the triangle hit (a heightfield: 0)
};

// A base-colour texture of a ground mesh: 8-bit sRGB RGBA, top row first (glTF: uv (0, 0) is the top left).
struct GroundTexture {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// A ground mesh's material: what the scene selects vegetation by, and what the ground is drawn with.
struct GroundMaterial {
    std::string name;          // glTF material name; may be empty
    glm::vec4 baseColor{1.0f}; // linear RGBA base colour factor
    int texture = -1;          // index into TriangleMesh::textures (multiplies baseColor), or -1
};

// Indexed triangle list in sward's world frame (metres, Z up).
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;          // 3 per triangle
    std::vector<glm::vec3> normals;         // optional: one unit shading normal per position (empty = flat)
    std::vector<glm::vec2> uvs;             // optional: one texture coordinate per position (empty = none)
    std::vector<uint32_t> triangleMaterial; // optional: one index into materials per triangle
    std::vector<GroundMaterial> materials;
    std::vector<GroundTexture> textures;
};

// Where vegetation may grow on a ground: the surfaces of the named materials (empty = every material), and only
// where the ground is no steeper than maxSlopeDegrees.
struct GroundSelection {
    std::vector<std::string> materials;
    double maxSlopeDegrees = 90.0;
};

class Ground {
public:
    Ground() = default;
    explicit Ground(Heightfield heightfield, GroundSelection selection = {});
    // Requires at least one non-vertical triangle, every index < positions.size(), normals / triangleMaterial empty
    // or one per position / triangle, material indices in range (throws sward::Error). cellSize 0 picks a grid cell
    // of about two mean triangle edges.
    explicit Ground(TriangleMesh mesh, GroundSelection selection = {}, float cellSize = 0.0f);

    // The top-most ground surface at xy, or nothing where no ground covers xy (outside the heightfield or mesh).
    std::optional<SurfacePoint> surface(glm::vec2 xy) const;
    // Height of the top-most surface at xy, with xy clamped into the bounds; where a mesh has a hole there, the
    // lowest height of the ground. For cameras and vehicles placed "above the ground", never for plants.
    float height(glm::vec2 xy) const;
    // Distance t along a unit-length ray to the first hit of the drawn surface, if any within maxDistance.
    std::optional<double> raycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const;

    glm::vec2 boundsMin() const { return boundsMin_; } // xy extent covered
    glm::vec2 boundsMax() const { return boundsMax_; }
    float minHeight() const { return minHeight_; } // z extent of the drawn surface
    float maxHeight() const { return maxHeight_; }
    const Heightfield* heightfield() const { return heightfield_ ? &*heightfield_ : nullptr; }
    const TriangleMesh* mesh() const { return heightfield_ ? nullptr : &mesh_; }
    // Mesh triangles vegetation may grow on (a heightfield: 0).
    uint32_t plantableTriangles() const { return plantableTriangles_; }

private:
    std::optional<SurfacePoint> meshSurface(glm::vec2 xy) const;
    std::optional<double> meshRaycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const;

    std::optional<Heightfield> heightfield_;
    TriangleMesh mesh_;
    glm::vec2 boundsMin_{0.0f}, boundsMax_{0.0f};
    float minHeight_ = 0.0f, maxHeight_ = 0.0f;
    // Slope limit as the smallest allowed normal z (0: no limit; heightfield and mesh alike).
    float minNormalZ_ = 0.0f;
    std::vector<uint8_t> plantable_; // per mesh triangle: its material is selected
    uint32_t plantableTriangles_ = 0;
    // Uniform grid over the mesh's xy bounds in CSR form: triangles of cell c are
    // cellTriangles_[cellStart_[c] .. cellStart_[c + 1]).
    float cellSize_ = 1.0f;
    uint32_t gridWidth_ = 0, gridHeight_ = 0;
    std::vector<uint32_t> cellStart_, cellTriangles_;
};

} // namespace sward
