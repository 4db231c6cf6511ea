#include "render/ground_mesh.h"

#include "vegetation/atlas_colour.h"
#include "world/heightfield_mesh.h"

#include <algorithm>
#include <array>
#include <bit>

namespace sward {

namespace {

GroundDrawMesh heightfieldDrawMesh(const Heightfield& terrain) {
    GroundDrawMesh out;
    out.vertices.reserve(size_t(terrain.columns()) * terrain.rows());
    for (uint32_t j = 0; j < terrain.rows(); ++j)
        for (uint32_t i = 0; i < terrain.columns(); ++i)
            out.vertices.push_back({glm::vec4(heightfieldVertex(terrain, i, j), 1.0f),
                                    glm::vec4(terrain.vertexNormal(i, j), 0.0f), glm::vec4(0.0f),
                                    glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)});
    out.indices = heightfieldTriangleIndices(terrain);
    return out;
}

const GroundMaterial* materialOf(const TriangleMesh& mesh, size_t triangle) {
    return mesh.triangleMaterial.empty() ? nullptr : &mesh.materials[mesh.triangleMaterial[triangle]];
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
        const GroundMaterial* material = materialOf(mesh, t);
        const glm::vec4 albedo(material ? glm::vec3(material->baseColor) : glm::vec3(1.0f), 1.0f);
        const float layer = material && material->texture >= 0 ? float(material->texture) : -1.0f;
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        glm::vec3 face = glm::cross(b - a, c - a);
        const bool clockwise = face.z < 0.0f;
        face = glm::dot(face, face) > 0.0f ? glm::normalize(clockwise ? -face : face) : glm::vec3(0, 0, 1);
        for (int k : {0, clockwise ? 2 : 1, clockwise ? 1 : 2}) {
            const uint32_t v = mesh.indices[3 * t + size_t(k)];
            const glm::vec3 normal = mesh.normals.empty() ? face : mesh.normals[v];
            out.indices.push_back(uint32_t(out.vertices.size()));
            const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
            out.vertices.push_back(
                {glm::vec4(mesh.positions[v], 1.0f), glm::vec4(normal, 0.0f), albedo, glm::vec4(uv, layer, 0.0f)});
        }
    }
    return out;
}

// Bilinear sample of an sRGB RGBA8 texture in linear light (alpha linear), at texel-centre coordinates, clamped.
glm::vec4 sampleLinear(const GroundTexture& t, float x, float y) {
    const auto& toLinear = atlas_detail::srgbTable().toLinear;
    x = std::clamp(x - 0.5f, 0.0f, float(t.width - 1));
    y = std::clamp(y - 0.5f, 0.0f, float(t.height - 1));
    const uint32_t x0 = uint32_t(x), y0 = uint32_t(y);
    const uint32_t x1 = std::min(x0 + 1, t.width - 1), y1 = std::min(y0 + 1, t.height - 1);
    const float fx = x - float(x0), fy = y - float(y0);
    auto texel = [&](uint32_t i, uint32_t j) {
        const uint8_t* p = &t.rgba[(size_t(j) * t.width + i) * 4];
        return glm::vec4(toLinear[p[0]], toLinear[p[1]], toLinear[p[2]], float(p[3]) / 255.0f);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), fx), glm::mix(texel(x0, y1), texel(x1, y1), fx), fy);
}

void appendEncoded(std::vector<uint8_t>& out, const std::vector<glm::vec4>& linear) {
    for (const glm::vec4& c : linear) {
        for (int k = 0; k < 3; ++k) out.push_back(atlas_detail::encodeSrgb(c[k]));
        out.push_back(atlas_detail::encodeUnorm(c.a));
    }
}

} // namespace

GroundTextureArray groundTextureArray(const Ground& ground) {
    const TriangleMesh* mesh = ground.mesh();
    if (!mesh || mesh->textures.empty()) return {.levels = {{255, 255, 255, 255}}};
    uint32_t largest = 1;
    for (const GroundTexture& t : mesh->textures) largest = std::max({largest, t.width, t.height});
    GroundTextureArray out;
    out.size = std::min(std::bit_ceil(largest), kMaxGroundTextureLayerSize);
    out.layers = uint32_t(mesh->textures.size());
    out.mipLevels = uint32_t(std::bit_width(out.size));
    // Level 0 resampled from each texture, then each level the 2x2 mean of the one before, all in linear light.
    std::vector<std::vector<glm::vec4>> layers(out.layers);
    for (uint32_t l = 0; l < out.layers; ++l) {
        const GroundTexture& t = mesh->textures[l];
        layers[l].resize(size_t(out.size) * out.size);
        for (uint32_t y = 0; y < out.size; ++y)
            for (uint32_t x = 0; x < out.size; ++x)
                layers[l][size_t(y) * out.size + x] = sampleLinear(t, (float(x) + 0.5f) * float(t.width) / float(out.size),
                                                                   (float(y) + 0.5f) * float(t.height) / float(out.size));
    }
    for (uint32_t level = 0, size = out.size; level < out.mipLevels; ++level, size /= 2) {
        out.levels.emplace_back();
        for (std::vector<glm::vec4>& texels : layers) {
            appendEncoded(out.levels.back(), texels);
            if (size == 1) continue;
            std::vector<glm::vec4> half(size_t(size / 2) * (size / 2));
            for (uint32_t y = 0; y < size / 2; ++y)
                for (uint32_t x = 0; x < size / 2; ++x)
                    half[size_t(y) * (size / 2) + x] =
                        0.25f * (texels[size_t(2 * y) * size + 2 * x] + texels[size_t(2 * y) * size + 2 * x + 1] +
                                 texels[size_t(2 * y + 1) * size + 2 * x] + texels[size_t(2 * y + 1) * size + 2 * x + 1]);
            texels = std::move(half);
        }
    }
    return out;
}

GroundDrawMesh groundDrawMesh(const Ground& ground) {
    return ground.heightfield() ? heightfieldDrawMesh(*ground.heightfield()) : meshDrawMesh(*ground.mesh());
}

namespace {

// The draw mesh's three vertex indices of the triangle under xy (clamped into the ground).
std::array<uint32_t, 3> drawTriangleAt(const Ground& ground, const GroundDrawMesh& mesh, glm::vec2 xy) {
    xy = glm::clamp(xy, ground.boundsMin(), ground.boundsMax());
    if (const Heightfield* h = ground.heightfield()) {
        // The cell and half Heightfield::height() interpolates: split along (i, j)-(i+1, j+1).
        const float u = std::clamp((xy.x - h->origin().x) / h->spacing(), 0.0f, float(h->columns() - 1));
        const float v = std::clamp((xy.y - h->origin().y) / h->spacing(), 0.0f, float(h->rows() - 1));
        const uint32_t i = std::min(uint32_t(u), h->columns() - 2), j = std::min(uint32_t(v), h->rows() - 2);
        const uint32_t p00 = j * h->columns() + i, p10 = p00 + 1, p01 = p00 + h->columns(), p11 = p01 + 1;
        return u - float(i) >= v - float(j) ? std::array{p00, p10, p11} : std::array{p00, p11, p01};
    }
    const std::optional<SurfacePoint> s = ground.surface(xy);
    const uint32_t t = s ? s->triangle : 0; // a hole in the mesh: any triangle's attributes will do
    return {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
}

} // namespace

gpu::TerrainVertex groundVertexAt(const Ground& ground, const GroundDrawMesh& mesh, glm::vec2 xy) {
    const auto [ia, ib, ic] = drawTriangleAt(ground, mesh, xy);
    const gpu::TerrainVertex &a = mesh.vertices[ia], &b = mesh.vertices[ib], &c = mesh.vertices[ic];
    const glm::dvec2 pa(a.positionHeight), pb(b.positionHeight), pc(c.positionHeight), p(xy);
    const double area = (pb.x - pa.x) * (pc.y - pa.y) - (pb.y - pa.y) * (pc.x - pa.x);
    double w0 = 1.0, w1 = 0.0;
    if (area != 0.0) {
        w0 = ((pb.x - p.x) * (pc.y - p.y) - (pb.y - p.y) * (pc.x - p.x)) / area;
        w1 = ((pc.x - p.x) * (pa.y - p.y) - (pc.y - p.y) * (pa.x - p.x)) / area;
    }
    const float fa = float(w0), fb = float(w1), fc = float(1.0 - w0 - w1);
    auto mix = [&](glm::vec4 ga, glm::vec4 gb, glm::vec4 gc) { return ga * fa + gb * fb + gc * fc; };
    gpu::TerrainVertex out;
    out.positionHeight = glm::vec4(xy, ground.height(xy), 0.0f);
    out.normal = glm::vec4(glm::normalize(glm::vec3(mix(a.normal, b.normal, c.normal))), 0.0f);
    out.albedo = mix(a.albedo, b.albedo, c.albedo);
    out.uvLayer =
        glm::vec4(glm::vec2(mix(a.uvLayer, b.uvLayer, c.uvLayer)), a.uvLayer.z, 0.0f); // one layer per triangle
    return out;
}

} // namespace sward
