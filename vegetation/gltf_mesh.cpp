// This translation unit holds tinygltf's implementation for all of sward: link sward_vegetation rather than
// defining TINYGLTF_IMPLEMENTATION again. stb_image comes compiled from Debian's libstb.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "gltf_mesh.h"

#include "error.h"

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sward {

namespace {

// Ground meshes need no textures: skip decoding images entirely.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

struct GltfReader {
    const std::string& path;
    const tinygltf::Model& model;
    TriangleMesh mesh;

    [[noreturn]] void fail(const std::string& problem) const { throw Error("glTF ground '" + path + "': " + problem); }

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

    void addPrimitive(const tinygltf::Primitive& prim, const glm::dmat4& transform) {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
            mode == TINYGLTF_MODE_LINE_STRIP)
            return; // not a surface
        if (mode != TINYGLTF_MODE_TRIANGLES)
            fail("primitive mode " + std::to_string(mode) + " is not supported (only triangle lists)");
        auto position = prim.attributes.find("POSITION");
        if (position == prim.attributes.end()) fail("a triangle primitive has no POSITION attribute");
        if (model.accessors.at(size_t(position->second)).componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail("POSITION must be float");
        const View positions = view(position->second, TINYGLTF_TYPE_VEC3, 12);
        const uint32_t base = uint32_t(mesh.positions.size());
        for (size_t i = 0; i < positions.count; ++i) {
            float v[3];
            std::memcpy(v, positions.data + i * positions.stride, sizeof v);
            glm::dvec4 p = transform * glm::dvec4(v[0], v[1], v[2], 1.0);
            mesh.positions.emplace_back(float(p.x), float(-p.z), float(p.y)); // Y-up -> Z-up
        }
        if (prim.indices < 0) {
            for (uint32_t i = 0; i + 2 < positions.count; i += 3)
                mesh.indices.insert(mesh.indices.end(), {base + i, base + i + 1, base + i + 2});
        } else {
            const int type = model.accessors.at(size_t(prim.indices)).componentType;
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
                if (index >= positions.count) fail("index " + std::to_string(index) + " exceeds the vertex count");
                mesh.indices.push_back(base + index);
            }
        }
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

    void addNode(int index, const glm::dmat4& parent, int depth) {
        if (index < 0 || size_t(index) >= model.nodes.size()) fail("node index out of range");
        if (depth > 64) fail("node hierarchy deeper than 64 levels (cycle?)");
        const tinygltf::Node& node = model.nodes[index];
        const glm::dmat4 transform = parent * localTransform(node);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size()) fail("node refers to a missing mesh");
            for (const tinygltf::Primitive& prim : model.meshes[node.mesh].primitives) addPrimitive(prim, transform);
        }
        for (int child : node.children) addNode(child, transform, depth + 1);
    }
};

} // namespace

TriangleMesh loadGltfMesh(const std::string& path) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(ignoreImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                             path.compare(path.size() - 4, 4, ".GLB") == 0);
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    require(ok, "cannot load glTF ground '" + path + "': " + (err.empty() ? "unknown error" : err));

    GltfReader reader{path, model, {}};
    if (!model.scenes.empty()) {
        const size_t scene = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        if (scene >= model.scenes.size()) reader.fail("default scene index out of range");
        for (int node : model.scenes[scene].nodes) reader.addNode(node, glm::dmat4(1.0), 0);
    } else {
        // No scene: take every mesh untransformed, as viewers do.
        for (const tinygltf::Mesh& mesh : model.meshes)
            for (const tinygltf::Primitive& prim : mesh.primitives) reader.addPrimitive(prim, glm::dmat4(1.0));
    }
    if (reader.mesh.indices.empty()) reader.fail("the file contains no triangles");
    return std::move(reader.mesh);
}

} // namespace sward
