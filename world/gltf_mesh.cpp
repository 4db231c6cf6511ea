// This translation unit holds tinygltf's implementation for all of sward: link sward_vegetation rather than
// defining TINYGLTF_IMPLEMENTATION again. stb_image comes compiled from Debian's libstb.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "world/gltf_mesh.h"

#include "common/error.h"

#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sward {

namespace {

// Ground meshes and object models need no textures: skip decoding images entirely.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// glTF Y-up -> sward Z-up: (x, y, z) -> (x, -z, y). A rotation, so it keeps triangle winding.
glm::dvec3 toZUp(glm::dvec3 v) {
    return {v.x, -v.z, v.y};
}
const glm::dmat4 kZUpFromYUp(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, -1, 0, 0),
                             glm::dvec4(0, 0, 0, 1)); // columns: images of glTF x, y, z

// One triangle primitive as stored in the file (glTF frame): positions, optional normals, a triangle list.
struct RawPrimitive {
    std::vector<glm::vec3> positions, normals;
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
        const tinygltf::Accessor& a = model.accessors[accessorIndex];
        if (a.sparse.isSparse) fail("sparse accessors are not supported");
        if (a.type != expectType) fail("accessor " + std::to_string(accessorIndex) + " has the wrong element type");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
            fail("accessor " + std::to_string(accessorIndex) + " has no valid buffer view");
        const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
        if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size()) fail("buffer view refers to a missing buffer");
        const std::vector<unsigned char>& buffer = model.buffers[v.buffer].data;
        const size_t stride = v.byteStride ? v.byteStride : elementSize;
        const size_t begin = v.byteOffset + a.byteOffset;
        const size_t needed = a.count == 0 ? 0 : stride * (a.count - 1) + elementSize;
        if (stride < elementSize || a.byteOffset + needed > v.byteLength || v.byteOffset + v.byteLength > buffer.size())
            fail("accessor " + std::to_string(accessorIndex) + " reaches past the end of its buffer");
        return {buffer.data() + begin, stride, a.count};
    }

    std::vector<glm::vec3> floatVec3(int accessor, const char* what) const {
        if (accessor < 0 || size_t(accessor) >= model.accessors.size()) fail("accessor index out of range");
        if (model.accessors[size_t(accessor)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail(std::string(what) + " must be float");
        const View values = view(accessor, TINYGLTF_TYPE_VEC3, 12);
        std::vector<glm::vec3> out(values.count);
        for (size_t i = 0; i < values.count; ++i) std::memcpy(&out[i], values.data + i * values.stride, 12);
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
            if (index >= count) fail("index " + std::to_string(index) + " exceeds the vertex count");
            out.indices.push_back(index);
        }
        return true;
    }

    glm::dmat4 localTransform(const tinygltf::Node& node) const {
        if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
        glm::dmat4 m(1.0);
        if (node.translation.size() == 3)
            m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4)
            m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
        if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
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

    // The default scene's root nodes, or none when the file has no scene.
    std::vector<int> rootNodes() const {
        if (model.scenes.empty()) return {};
        const size_t scene = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        if (scene >= model.scenes.size()) fail("default scene index out of range");
        return model.scenes[scene].nodes;
    }
};

tinygltf::Model readFile(const std::string& path, const char* kind) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(ignoreImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                             path.compare(path.size() - 4, 4, ".GLB") == 0);
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    require(ok, "cannot load " + std::string(kind) + " '" + path + "': " + (err.empty() ? "unknown error" : err));
    return model;
}

// Ground: every primitive flattened into one world-space mesh.
struct MeshBuilder {
    const GltfReader& reader;
    TriangleMesh mesh;

    void addPrimitive(const tinygltf::Primitive& prim, const glm::dmat4& transform) {
        RawPrimitive raw;
        if (!reader.readPrimitive(prim, false, raw)) return;
        const uint32_t base = uint32_t(mesh.positions.size());
        for (const glm::vec3& v : raw.positions)
            mesh.positions.push_back(glm::vec3(toZUp(glm::dvec3(transform * glm::dvec4(glm::dvec3(v), 1.0)))));
        for (uint32_t index : raw.indices) mesh.indices.push_back(base + index);
    }

    void addNode(int index, const glm::dmat4& parent, int depth) {
        const tinygltf::Node& node = reader.node(index, depth);
        const glm::dmat4 transform = parent * reader.localTransform(node);
        if (node.mesh >= 0)
            for (const tinygltf::Primitive& prim : reader.model.meshes[size_t(node.mesh)].primitives)
                addPrimitive(prim, transform);
        for (int child : node.children) addNode(child, transform, depth + 1);
    }
};

// Objects: the node tree kept, each mesh in its node's own frame.
struct ModelBuilder {
    const GltfReader& reader;
    ObjectModel result;

    glm::vec4 baseColor(int material) const {
        if (material < 0) return glm::vec4(1.0f);
        if (size_t(material) >= reader.model.materials.size()) reader.fail("a primitive refers to a missing material");
        const std::vector<double>& f = reader.model.materials[size_t(material)].pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4) reader.fail("baseColorFactor must have 4 components");
        return glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    }

    // `mirrored`: the node's transform flips handedness, so the winding is reversed to keep fronts outside.
    void addMesh(int mesh, ModelNode& target, bool mirrored) {
        for (const tinygltf::Primitive& prim : reader.model.meshes[size_t(mesh)].primitives) {
            RawPrimitive raw;
            if (!reader.readPrimitive(prim, true, raw) || raw.indices.empty()) continue;
            ModelPrimitive out;
            out.baseColor = baseColor(prim.material);
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
        out.local = kZUpFromYUp * reader.localTransform(node) * glm::transpose(kZUpFromYUp);
        out.modelFromNode = parent < 0 ? out.local : result.nodes[size_t(parent)].modelFromNode * out.local;
        if (node.mesh >= 0) addMesh(node.mesh, out, glm::determinant(out.modelFromNode) < 0.0);
        const int self = int(result.nodes.size());
        result.nodes.push_back(std::move(out));
        for (int child : node.children) addNode(child, self, depth + 1);
    }
};

} // namespace

TriangleMesh loadGltfMesh(const std::string& path) {
    const tinygltf::Model model = readFile(path, "glTF ground");
    GltfReader reader{path, model, "glTF ground"};
    MeshBuilder builder{reader, {}};
    if (!model.scenes.empty()) {
        for (int node : reader.rootNodes()) builder.addNode(node, glm::dmat4(1.0), 0);
    } else {
        // No scene: take every mesh untransformed, as viewers do.
        for (const tinygltf::Mesh& mesh : model.meshes)
            for (const tinygltf::Primitive& prim : mesh.primitives) builder.addPrimitive(prim, glm::dmat4(1.0));
    }
    if (builder.mesh.indices.empty()) reader.fail("the file contains no triangles");
    return std::move(builder.mesh);
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

ObjectModel loadGltfModel(const std::string& path) {
    const tinygltf::Model model = readFile(path, "glTF model");
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
