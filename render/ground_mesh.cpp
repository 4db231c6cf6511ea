#include "render/ground_mesh.h"

namespace sward {

namespace {

GroundDrawMesh heightfieldDrawMesh(const Heightfield& terrain) {
    GroundDrawMesh out;
    out.vertices.reserve(size_t(terrain.columns()) * terrain.rows());
    for (uint32_t j = 0; j < terrain.rows(); ++j)
        for (uint32_t i = 0; i < terrain.columns(); ++i) {
            const glm::vec2 xy = terrain.origin() + glm::vec2(float(i), float(j)) * terrain.spacing();
            out.vertices.push_back({glm::vec4(xy, terrain.sample(i, j), 1.0f),
                                    glm::vec4(terrain.vertexNormal(i, j), 0.0f), glm::vec4(0.0f)});
        }
    out.indices.reserve(size_t(terrain.columns() - 1) * (terrain.rows() - 1) * 6);
    for (uint32_t j = 0; j + 1 < terrain.rows(); ++j)
        for (uint32_t i = 0; i + 1 < terrain.columns(); ++i) {
            const uint32_t p00 = j * terrain.columns() + i, p10 = p00 + 1, p01 = p00 + terrain.columns(), p11 = p01 + 1;
            out.indices.insert(out.indices.end(), {p00, p10, p11, p00, p11, p01});
        }
    return out;
}

glm::vec4 materialAlbedo(const TriangleMesh& mesh, size_t triangle) {
    const glm::vec4 base = mesh.triangleMaterial.empty() ? glm::vec4(1.0f)
                                                          : mesh.materials[mesh.triangleMaterial[triangle]].baseColor;
    return glm::vec4(glm::vec3(base), 1.0f);
}

// Every corner gets a vertex of its own: its triangle's material colour, and the file's normal (smooth shading) or
// the face normal (flat, as Ground::surface evaluates). Triangles are wound counter-clockwise seen from above, as
// the heightfield's, whatever the file's winding or node mirroring.
GroundDrawMesh meshDrawMesh(const TriangleMesh& mesh) {
    GroundDrawMesh out;
    const size_t triangles = mesh.indices.size() / 3;
    out.vertices.reserve(mesh.indices.size());
    out.indices.reserve(mesh.indices.size());
    for (size_t t = 0; t < triangles; ++t) {
        const glm::vec4 albedo = materialAlbedo(mesh, t);
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        glm::vec3 face = glm::cross(b - a, c - a);
        const bool clockwise = face.z < 0.0f;
        face = glm::dot(face, face) > 0.0f ? glm::normalize(clockwise ? -face : face) : glm::vec3(0, 0, 1);
        for (int k : {0, clockwise ? 2 : 1, clockwise ? 1 : 2}) {
            const uint32_t v = mesh.indices[3 * t + size_t(k)];
            const glm::vec3 normal = mesh.normals.empty() ? face : mesh.normals[v];
            out.indices.push_back(uint32_t(out.vertices.size()));
            out.vertices.push_back({glm::vec4(mesh.positions[v], 1.0f), glm::vec4(normal, 0.0f), albedo});
        }
    }
    return out;
}

} // namespace

GroundDrawMesh groundDrawMesh(const Ground& ground) {
    return ground.heightfield() ? heightfieldDrawMesh(*ground.heightfield()) : meshDrawMesh(*ground.mesh());
}

} // namespace sward
