// This translation unit holds tinygltf's implementation for all of sward: link sward_vegetation rather than
// defining TINYGLTF_IMPLEMENTATION again. stb_image comes compiled from Debian's libstb.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "world/gltf_mesh.h"

#include "common/error.h"
#include "world/gltf_files.h"
#include "world/gltf_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sward {

namespace {

// glTF Y-up -> sward Z-up: (x, y, z) -> (x, -z, y). A rotation, so it keeps triangle winding.
// Largest coordinate (metres) of a vertex and largest entry of a node transform: far beyond any ground or model,
// small enough that every product of them stays finite in float.
constexpr double kMaxCoordinate = 1e8;

glm::dvec3 toZUp(glm::dvec3 v) {
    return {v.x, -v.z, v.y};
}
const glm::dmat4 kZUpFromYUp(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, -1, 0, 0),
                             glm::dvec4(0, 0, 0, 1)); // columns: images of glTF x, y, z

// One triangle primitive as stored in the file (glTF frame): positions, optional normals, a triangle list.
struct RawPrimitive {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs; // TEXCOORD_0, ground meshes only
    std::vector<uint32_t> indices;
};

struct GltfReader {
    const std::string& path;
    const tinygltf::Model& model;
    const char* kind; // "glTF ground", "glTF model": names the file's role in messages

    [[noreturn]] void fail(const std::string& problem) const {
        throw Error(std::string(kind) + " '" + path + "': " + problem);
    }

    // Bounds-checked view of one accessor: element i starts at data + i * stride.
    struct View {
        const unsigned char* data;
        size_t stride, count;
    };
    View view(int accessorIndex, int expectType, size_t elementSize) const {
        if (accessorIndex < 0 || size_t(accessorIndex) >= model.accessors.size()) fail("accessor index out of range");
        const std::string name = "accessor " + std::to_string(accessorIndex);
        const tinygltf::Accessor& a = model.accessors[size_t(accessorIndex)];
        if (a.sparse.isSparse) fail("sparse accessors are not supported");
        if (a.type != expectType) fail(name + " has the wrong element type");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
            fail(name + " has no valid buffer view");
        const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
        if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size()) fail("buffer view refers to a missing buffer");
        const std::vector<unsigned char>& buffer = model.buffers[size_t(v.buffer)].data;
        const size_t stride = v.byteStride ? v.byteStride : elementSize;
        if (stride < elementSize) fail(name + "'s buffer view has a byteStride smaller than its elements");
        // Every number here comes from the file: compare by subtraction and division, never by a sum or product
        // that could wrap (a count near 2^62 times the stride wraps to a small number).
        if (v.byteOffset > buffer.size() || v.byteLength > buffer.size() - v.byteOffset)
            fail("buffer view " + std::to_string(a.bufferView) + " reaches past the end of its buffer");
        if (a.byteOffset > v.byteLength) fail(name + " starts past the end of its buffer view");
        const size_t room = v.byteLength - a.byteOffset;
        if (a.count > 0 && (elementSize > room || (a.count - 1) > (room - elementSize) / stride))
            fail(name + " (" + std::to_string(a.count) + " elements) reaches past the end of buffer view " +
                 std::to_string(a.bufferView));
        return {buffer.data() + v.byteOffset + a.byteOffset, stride, a.count};
    }

    // Positions must also lie within kMaxCoordinate metres, so that every transformed vertex stays finite in
    // float; non-finite values are refused for both positions and normals.
    std::vector<glm::vec3> floatVec3(int accessor, const char* what) const {
        if (accessor < 0 || size_t(accessor) >= model.accessors.size()) fail("accessor index out of range");
        if (model.accessors[size_t(accessor)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail(std::string(what) + " must be float");
        const View values = view(accessor, TINYGLTF_TYPE_VEC3, 12);
        const bool position = std::string(what) == "POSITION";
        std::vector<glm::vec3> out(values.count);
        for (size_t i = 0; i < values.count; ++i) {
            std::memcpy(&out[i], values.data + i * values.stride, 12);
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(out[i][c]) || (position && std::abs(out[i][c]) > kMaxCoordinate))
                    fail("accessor " + std::to_string(accessor) + " (" + what + "): element " + std::to_string(i) +
                         (position ? " is not finite or beyond 1e8 m" : " is not finite"));
        }
        return out;
    }

    // TEXCOORD_n: float, or unsigned byte / short normalised to [0, 1] (glTF allows all three); finite.
    std::vector<glm::vec2> texCoords(int accessor) const {
        if (accessor < 0 || size_t(accessor) >= model.accessors.size()) fail("accessor index out of range");
        const tinygltf::Accessor& a = model.accessors[size_t(accessor)];
        const int type = a.componentType;
        const size_t component = type == TINYGLTF_COMPONENT_TYPE_FLOAT            ? 4
                                 : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                 : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                                                                                  : 0;
        if (component == 0 || (component < 4 && !a.normalized))
            fail("TEXCOORD must be float or normalised unsigned byte / short");
        const View values = view(accessor, TINYGLTF_TYPE_VEC2, 2 * component);
        std::vector<glm::vec2> out(values.count);
        for (size_t i = 0; i < values.count; ++i) {
            const unsigned char* at = values.data + i * values.stride;
            for (int c = 0; c < 2; ++c) {
                const unsigned char* v = at + size_t(c) * component;
                uint16_t u16 = 0;
                float f = 0.0f;
                if (component == 4) std::memcpy(&f, v, 4);
                else if (component == 2) std::memcpy(&u16, v, 2), f = float(u16) / 65535.0f;
                else f = float(*v) / 255.0f;
                if (!(std::abs(f) <= 1e6f)) fail("accessor " + std::to_string(accessor) + " (TEXCOORD) is not finite");
                out[i][c] = f;
            }
        }
        return out;
    }

    // Reads a triangle primitive; returns false for points and lines (not a surface).
    bool readPrimitive(const tinygltf::Primitive& prim, bool wantNormals, RawPrimitive& out) const {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
            mode == TINYGLTF_MODE_LINE_STRIP)
            return false;
        if (mode != TINYGLTF_MODE_TRIANGLES)
            fail("primitive mode " + std::to_string(mode) + " is not supported (only triangle lists)");
        auto position = prim.attributes.find("POSITION");
        if (position == prim.attributes.end()) fail("a triangle primitive has no POSITION attribute");
        out.positions = floatVec3(position->second, "POSITION");
        if (out.positions.size() > std::numeric_limits<uint32_t>::max())
            fail("a primitive has more than 2^32 vertices");
        const uint32_t count = uint32_t(out.positions.size());
        if (wantNormals) {
            auto normal = prim.attributes.find("NORMAL");
            if (normal != prim.attributes.end()) {
                out.normals = floatVec3(normal->second, "NORMAL");
                if (out.normals.size() != out.positions.size()) fail("NORMAL and POSITION counts differ");
            }
        }
        if (prim.indices < 0) {
            for (uint32_t i = 0; i + 2 < count; i += 3) out.indices.insert(out.indices.end(), {i, i + 1, i + 2});
            return true;
        }
        if (size_t(prim.indices) >= model.accessors.size()) fail("accessor index out of range");
        const int type = model.accessors[size_t(prim.indices)].componentType;
        const size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                            : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                            : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                             : 0;
        if (size == 0) fail("indices must be unsigned byte, short or int");
        const View indices = view(prim.indices, TINYGLTF_TYPE_SCALAR, size);
        for (size_t i = 0; i < indices.count - indices.count % 3; ++i) {
            uint32_t index = 0;
            const unsigned char* at = indices.data + i * indices.stride;
            if (size == 1)
                index = *at;
            else if (size == 2)
                index = uint32_t(at[0] | at[1] << 8);
            else
                std::memcpy(&index, at, 4);
            // The value is not quoted: it comes from a buffer file, which may be any file the scene may read.
            if (index >= count)
                fail("accessor " + std::to_string(prim.indices) + " (indices): element " + std::to_string(i) +
                     " is not below the vertex count " + std::to_string(count));
            out.indices.push_back(index);
        }
        return true;
    }

    // The node's parent-from-node transform (glTF frame). JSON holds no infinity (tinygltf refuses 1e999), but
    // a finite 1e308 is just as fatal once multiplied: each value must lie within kMaxCoordinate.
    glm::dmat4 localTransform(int index, const tinygltf::Node& node) const {
        auto bounded = [&](const std::vector<double>& values, const char* key) {
            for (double v : values)
                if (!(std::abs(v) <= kMaxCoordinate))
                    fail(nodeName(index, node) + ": '" + key + "' holds a value beyond 1e8 (or not finite)");
        };
        bounded(node.matrix, "matrix");
        bounded(node.translation, "translation");
        bounded(node.rotation, "rotation");
        bounded(node.scale, "scale");
        if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
        glm::dmat4 m(1.0);
        if (node.translation.size() == 3)
            m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4)
            m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
        if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
    }

    // A node's transform composed with its parents' must keep every vertex finite in float: each entry within
    // kMaxCoordinate (a scale of 1e308 is finite in double but not in anything drawn).
    void checkComposed(int index, const tinygltf::Node& node, const glm::dmat4& m) const {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r]) || std::abs(m[c][r]) > kMaxCoordinate)
                    fail(nodeName(index, node) + ": its transform (with its parents') is not finite or has an entry "
                                                 "beyond 1e8 (a huge scale or translation?)");
    }

    static std::string nodeName(int index, const tinygltf::Node& node) {
        return "node " + std::to_string(index) + (node.name.empty() ? "" : " ('" + node.name + "')");
    }

    // glTF nodes form a strict tree; a node reached twice would be a cycle or a shared subtree, whose visits can
    // grow exponentially with depth in a hostile file.
    mutable std::vector<bool> visited = std::vector<bool>(model.nodes.size(), false);

    const tinygltf::Node& node(int index, int depth) const {
        if (index < 0 || size_t(index) >= model.nodes.size()) fail("node index out of range");
        if (depth > 64) fail("node hierarchy deeper than 64 levels (cycle?)");
        if (visited[size_t(index)])
            fail("node " + std::to_string(index) + " is used more than once (glTF nodes must form a tree)");
        visited[size_t(index)] = true;
        const tinygltf::Node& n = model.nodes[size_t(index)];
        if (n.mesh >= 0 && size_t(n.mesh) >= model.meshes.size()) fail("node refers to a missing mesh");
        return n;
    }

    // A material's linear RGBA base colour factor (glTF's default material: white).
    glm::vec4 baseColor(int material) const {
        if (material < 0) return glm::vec4(1.0f);
        if (size_t(material) >= model.materials.size()) fail("a primitive refers to a missing material");
        const std::vector<double>& f = model.materials[size_t(material)].pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4) fail("baseColorFactor must have 4 components");
        for (double v : f)
            if (!(v >= 0.0 && v <= 1.0)) fail("baseColorFactor components must lie in [0, 1]");
        return glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    }

    // The default scene's root nodes, or none when the file has no scene.
    std::vector<int> rootNodes() const {
        if (model.scenes.empty()) return {};
        const size_t scene = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        if (scene >= model.scenes.size()) fail("default scene index out of range");
        return model.scenes[scene].nodes;
    }
};

// Ground: every primitive flattened into one world-space mesh, with its material per triangle and its normals
// (when every primitive has them).
struct MeshBuilder {
    const GltfReader& reader;
    const AssetPolicy& assets; // external texture images are read only where it allows
    TriangleMesh mesh;
    std::vector<int> materialOf;     // glTF material index + 1 (0: the default material) -> mesh.materials index
    std::vector<int> textureOf;      // glTF texture index -> mesh.textures index
    std::map<int, int> imageTexture; // glTF image index -> mesh.textures index: one decode per image
    uint64_t textureBytes = 0;       // of mesh.textures, priced against kMaxGroundTextureBytes
    bool normalsEverywhere = true;   // every primitive so far had NORMAL
    bool uvsEverywhere = true;       // every primitive so far had TEXCOORD_0

    int texture(int gltfTexture) {
        if (textureOf.empty()) textureOf.assign(reader.model.textures.size(), -1);
        if (gltfTexture < 0 || size_t(gltfTexture) >= textureOf.size())
            reader.fail("a material's baseColorTexture refers to a missing texture");
        int& index = textureOf[size_t(gltfTexture)];
        if (index >= 0) return index;
        // Textures that share an image share its pixels: 20 materials over one 8192^2 image took 5.9 GB.
        const int image = reader.model.textures[size_t(gltfTexture)].source;
        if (auto known = imageTexture.find(image); known != imageTexture.end()) return index = known->second;
        GroundTexture decoded = groundTexture(reader.model, gltfTexture,
                                              std::string(reader.kind) + " '" + reader.path + "'", assets, reader.path);
        textureBytes += uint64_t(decoded.width) * decoded.height * 4;
        if (textureBytes > kMaxGroundTextureBytes)
            reader.fail("its ground textures take " + std::to_string(textureBytes >> 20) + " MiB as RGBA (image " +
                        std::to_string(image) + " of " + std::to_string(decoded.width) + "x" +
                        std::to_string(decoded.height) + " among them), over the limit of " +
                        std::to_string(kMaxGroundTextureBytes >> 20) + " MiB");
        index = int(mesh.textures.size());
        imageTexture[image] = index;
        mesh.textures.push_back(std::move(decoded));
        return index;
    }

    uint32_t material(int gltfMaterial) {
        const glm::vec4 color = reader.baseColor(gltfMaterial);
        if (materialOf.empty()) materialOf.assign(reader.model.materials.size() + 1, -1);
        int& index = materialOf[size_t(gltfMaterial + 1)];
        if (index < 0) {
            GroundMaterial m{gltfMaterial < 0 ? "" : reader.model.materials[size_t(gltfMaterial)].name, color};
            if (gltfMaterial >= 0) {
                const tinygltf::TextureInfo& t = reader.model.materials[size_t(gltfMaterial)].pbrMetallicRoughness.baseColorTexture;
                if (t.index >= 0 && t.texCoord != 0) reader.fail("baseColorTexture uses TEXCOORD_" + std::to_string(t.texCoord) + "; only TEXCOORD_0 is read");
                if (t.index >= 0) m.texture = texture(t.index);
            }
            index = int(mesh.materials.size());
            mesh.materials.push_back(std::move(m));
        }
        return uint32_t(index);
    }

    void addPrimitive(const tinygltf::Primitive& prim, const glm::dmat4& transform) {
        RawPrimitive raw;
        if (!reader.readPrimitive(prim, true, raw)) return;
        if (auto uv = prim.attributes.find("TEXCOORD_0"); uv != prim.attributes.end()) {
            raw.uvs = reader.texCoords(uv->second);
            if (raw.uvs.size() != raw.positions.size()) reader.fail("TEXCOORD_0 and POSITION counts differ");
        }
        const uint32_t base = uint32_t(mesh.positions.size());
        for (const glm::vec3& v : raw.positions)
            mesh.positions.push_back(glm::vec3(toZUp(glm::dvec3(transform * glm::dvec4(glm::dvec3(v), 1.0)))));
        for (uint32_t index : raw.indices) mesh.indices.push_back(base + index);
        mesh.triangleMaterial.insert(mesh.triangleMaterial.end(), raw.indices.size() / 3, material(prim.material));
        normalsEverywhere = normalsEverywhere && !raw.normals.empty();
        uvsEverywhere = uvsEverywhere && !raw.uvs.empty();
        mesh.uvs.insert(mesh.uvs.end(), raw.uvs.begin(), raw.uvs.end());
        // Normals transform with the inverse transpose; a degenerate one falls back to up.
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(kZUpFromYUp * transform)));
        for (const glm::vec3& n : raw.normals) {
            const glm::dvec3 w = normalMatrix * glm::dvec3(n);
            const double length = glm::length(w);
            mesh.normals.push_back(length > 0.0 ? glm::vec3(w / length) : glm::vec3(0, 0, 1));
        }
    }

    void addNode(int index, const glm::dmat4& parent, int depth) {
        const tinygltf::Node& node = reader.node(index, depth);
        const glm::dmat4 transform = parent * reader.localTransform(index, node);
        reader.checkComposed(index, node, transform);
        if (node.mesh >= 0)
            for (const tinygltf::Primitive& prim : reader.model.meshes[size_t(node.mesh)].primitives)
                addPrimitive(prim, transform);
        for (int child : node.children) addNode(child, transform, depth + 1);
    }

    TriangleMesh finish() {
        if (!normalsEverywhere) mesh.normals.clear(); // flat shading for all rather than mixed
        if (!uvsEverywhere) mesh.uvs.clear();
        for (const GroundMaterial& m : mesh.materials)
            if (m.texture >= 0 && mesh.uvs.empty())
                reader.fail("material '" + m.name + "' has a baseColorTexture but not every primitive has TEXCOORD_0");
        return std::move(mesh);
    }
};

// Objects: the node tree kept, each mesh in its node's own frame.
struct ModelBuilder {
    const GltfReader& reader;
    ObjectModel result;

    // `mirrored`: the node's transform flips handedness, so the winding is reversed to keep fronts outside.
    void addMesh(int mesh, ModelNode& target, bool mirrored) {
        for (const tinygltf::Primitive& prim : reader.model.meshes[size_t(mesh)].primitives) {
            RawPrimitive raw;
            if (!reader.readPrimitive(prim, true, raw) || raw.indices.empty()) continue;
            ModelPrimitive out;
            out.baseColor = reader.baseColor(prim.material);
            if (mirrored)
                for (size_t t = 0; t < raw.indices.size(); t += 3) std::swap(raw.indices[t + 1], raw.indices[t + 2]);
            if (raw.normals.empty()) {
                // No normals in the file: flat shading, one vertex per triangle corner.
                for (size_t t = 0; t < raw.indices.size(); t += 3) {
                    glm::dvec3 a = toZUp(raw.positions[raw.indices[t]]), b = toZUp(raw.positions[raw.indices[t + 1]]),
                               c = toZUp(raw.positions[raw.indices[t + 2]]);
                    glm::dvec3 n = glm::cross(b - a, c - a);
                    double length = glm::length(n);
                    glm::vec3 normal = length > 0.0 ? glm::vec3(n / length) : glm::vec3(0, 0, 1);
                    if (mirrored) normal = -normal; // the face normal of the reversed triangle, in node space
                    for (const glm::dvec3& p : {a, b, c}) {
                        out.indices.push_back(uint32_t(out.positions.size()));
                        out.positions.push_back(glm::vec3(p));
                        out.normals.push_back(normal);
                    }
                }
            } else {
                for (const glm::vec3& p : raw.positions) out.positions.push_back(glm::vec3(toZUp(p)));
                for (const glm::vec3& n : raw.normals) {
                    glm::dvec3 z = toZUp(n);
                    double length = glm::length(z);
                    out.normals.push_back(length > 0.0 ? glm::vec3(z / length) : glm::vec3(0, 0, 1));
                }
                out.indices = std::move(raw.indices);
            }
            target.primitives.push_back(std::move(out));
        }
    }

    void addNode(int index, int parent, int depth) {
        const tinygltf::Node& node = reader.node(index, depth);
        ModelNode out;
        out.name = node.name;
        out.parent = parent;
        out.local = kZUpFromYUp * reader.localTransform(index, node) * glm::transpose(kZUpFromYUp);
        out.modelFromNode = parent < 0 ? out.local : result.nodes[size_t(parent)].modelFromNode * out.local;
        reader.checkComposed(index, node, out.modelFromNode);
        if (node.mesh >= 0) addMesh(node.mesh, out, glm::determinant(out.modelFromNode) < 0.0);
        const int self = int(result.nodes.size());
        result.nodes.push_back(std::move(out));
        for (int child : node.children) addNode(child, self, depth + 1);
    }
};

// The flattened ground's size, priced from the accessors' counts before a vertex is read: every node that uses a
// mesh copies all of its primitives, so one mesh of 100,000 triangles under 100,000 nodes asks for 10^10 (no frame
// after 600 s). Counts are those of accessors that fit their buffers (reader.view refuses the rest, as reading them
// would); what readPrimitive refuses for other reasons (a type, a mode) is left to it, as are nodes past the depth
// limit or reached twice.
void requireGroundBudget(const GltfReader& reader) {
    const tinygltf::Model& model = reader.model;
    auto valid = [&](int accessor) { return accessor >= 0 && size_t(accessor) < model.accessors.size(); };
    // Triangles and vertices of one copy of each mesh, each priced once however many nodes use it.
    std::vector<std::pair<uint64_t, uint64_t>> meshSizes(model.meshes.size());
    std::vector<bool> priced(model.meshes.size(), false);
    auto meshSize = [&](int index) {
        if (priced[size_t(index)]) return meshSizes[size_t(index)];
        uint64_t triangles = 0, vertices = 0;
        for (const tinygltf::Primitive& prim : model.meshes[size_t(index)].primitives) {
            if (prim.mode >= 0 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
            const auto position = prim.attributes.find("POSITION");
            if (position == prim.attributes.end() || !valid(position->second) ||
                model.accessors[size_t(position->second)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                continue;
            const uint64_t positions = reader.view(position->second, TINYGLTF_TYPE_VEC3, 12).count;
            vertices += positions;
            if (prim.indices < 0) {
                triangles += positions / 3;
                continue;
            }
            if (!valid(prim.indices)) continue;
            const int type = model.accessors[size_t(prim.indices)].componentType;
            const size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                                : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                 : 0;
            if (size > 0) triangles += reader.view(prim.indices, TINYGLTF_TYPE_SCALAR, size).count / 3;
        }
        priced[size_t(index)] = true;
        return meshSizes[size_t(index)] = {triangles, vertices};
    };
    // Each sum grows by at most a buffer's bytes a node (and a node is at least a few bytes of the file): no wrap.
    uint64_t triangles = 0, vertices = 0, instances = 0;
    auto add = [&](int mesh) {
        const auto [t, v] = meshSize(mesh);
        triangles += t, vertices += v, ++instances;
    };
    if (model.scenes.empty()) {
        for (size_t m = 0; m < model.meshes.size(); ++m) add(int(m));
    } else {
        std::vector<bool> seen(model.nodes.size(), false);
        std::vector<std::pair<int, int>> stack; // (node, depth)
        for (int root : reader.rootNodes()) stack.emplace_back(root, 0);
        while (!stack.empty()) {
            const auto [index, depth] = stack.back();
            stack.pop_back();
            if (index < 0 || size_t(index) >= model.nodes.size() || depth > 64 || seen[size_t(index)]) continue;
            seen[size_t(index)] = true;
            const tinygltf::Node& node = model.nodes[size_t(index)];
            if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) add(node.mesh);
            for (int child : node.children) stack.emplace_back(child, depth + 1);
        }
    }
    if (triangles > kMaxGroundTriangles || vertices > kMaxGroundTriangles)
        reader.fail(std::to_string(instances) + " mesh instances (nodes) would flatten into " +
                    std::to_string(triangles) + " triangles and " + std::to_string(vertices) +
                    " vertices, over the limit of " + std::to_string(kMaxGroundTriangles) +
                    " of each (instances x the triangles of their meshes)");
}

} // namespace

TriangleMesh loadGltfMesh(const std::string& path, const AssetPolicy& assets) {
    const tinygltf::Model model = readGltfFile(path, "glTF ground", assets, true);
    GltfReader reader{path, model, "glTF ground"};
    requireGroundBudget(reader);
    MeshBuilder builder{reader, assets, {}};
    if (!model.scenes.empty()) {
        for (int node : reader.rootNodes()) builder.addNode(node, glm::dmat4(1.0), 0);
    } else {
        // No scene: take every mesh untransformed, as viewers do.
        for (const tinygltf::Mesh& mesh : model.meshes)
            for (const tinygltf::Primitive& prim : mesh.primitives) builder.addPrimitive(prim, glm::dmat4(1.0));
    }
    if (builder.mesh.indices.empty()) reader.fail("the file contains no triangles");
    return builder.finish();
}

int ObjectModel::findNode(const std::string& name) const {
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == name) return int(i);
    return -1;
}

size_t ObjectModel::triangleCount() const {
    size_t count = 0;
    for (const ModelNode& node : nodes)
        for (const ModelPrimitive& prim : node.primitives) count += prim.indices.size() / 3;
    return count;
}

ObjectModel loadGltfModel(const std::string& path, const AssetPolicy& assets) {
    const tinygltf::Model model = readGltfFile(path, "glTF model", assets, false);
    GltfReader reader{path, model, "glTF model"};
    ModelBuilder builder{reader, {}};
    builder.result.path = path;
    if (!model.scenes.empty()) {
        for (int node : reader.rootNodes()) builder.addNode(node, -1, 0);
    } else {
        for (size_t m = 0; m < model.meshes.size(); ++m) {
            ModelNode node;
            builder.addMesh(int(m), node, false);
            builder.result.nodes.push_back(std::move(node));
        }
    }
    ObjectModel& result = builder.result;
    if (result.triangleCount() == 0) reader.fail("the file contains no triangles");
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const ModelNode& node : result.nodes)
        for (const ModelPrimitive& prim : node.primitives)
            for (const glm::vec3& p : prim.positions) {
                glm::dvec3 m = glm::dvec3(node.modelFromNode * glm::dvec4(glm::dvec3(p), 1.0));
                lo = glm::min(lo, m);
                hi = glm::max(hi, m);
            }
    result.boundsMin = glm::vec3(lo);
    result.boundsMax = glm::vec3(hi);
    return std::move(builder.result);
}

} // namespace sward
