// Ground meshes and object models from glTF 2.0 files (tinygltf).
//
// Both loaders convert glTF's Y-up frame to sward's Z-up frame with the rotation C: (x, y, z) -> (x, -z, y).
// A glTF asset faces +Z (glTF spec, "front of an asset"), so in sward's model frame its front is -y, its left
// (glTF +X) is +x and its top is +z.
#pragma once

#include "world/asset_policy.h"
#include "world/ground.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Loads every triangle primitive reachable from the default scene of a .gltf (embedded or external buffers) or
// .glb file, with node transforms applied and glTF's Y-up converted to sward's Z-up: (x, y, z) -> (x, -z, y); each
// triangle keeps its material (name and base colour factor; glTF's default material is named ""), and the mesh
// keeps the files' normals when every primitive has them.
// Throws sward::Error naming the file for a missing or malformed file, out-of-range accessors or indices, strip/fan
// primitives, sparse accessors, an extension in extensionsRequired (e.g. Draco compression), a non-finite node
// transform or vertex, a composed node transform with an entry beyond 1e8 or a vertex beyond 1e8 m, or a file
// without triangles. Points and lines are ignored. The buffer files it names are read only where `assets` allows
// (asset_policy.h); errors never quote a buffer file's bytes or size.
// A ground flattens to at most kMaxGroundTriangles triangles and as many vertices (every node's copy of its mesh
// counted), priced from the accessors before anything is read: about 1.5 GiB of mesh at the limit.
inline constexpr uint64_t kMaxGroundTriangles = uint64_t(1) << 24;
TriangleMesh loadGltfMesh(const std::string& path, const AssetPolicy& assets = {});

// One triangle primitive of a model node, in the node's own frame (converted to Z-up).
struct ModelPrimitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // unit, one per position: the file's NORMAL, else flat face normals
    std::vector<uint32_t> indices;  // triangle list, counter-clockwise seen from the front in the model frame
    glm::vec4 baseColor{1.0f};      // linear RGBA: the material's pbrMetallicRoughness.baseColorFactor (glTF default 1)
};

// A node of the model's hierarchy (the default scene's nodes, depth first: parents before their children).
struct ModelNode {
    std::string name;                       // glTF node name; may be empty
    int parent = -1;                        // index into ObjectModel::nodes; -1 for the scene's root nodes
    glm::dmat4 local{1.0};                  // parent-from-node transform, Z-up
    glm::dmat4 modelFromNode{1.0};          // model-from-node transform (all ancestors applied), Z-up
    std::vector<ModelPrimitive> primitives; // the node's mesh, if any (a mesh used by several nodes is copied)
};

// A glTF model with its node hierarchy kept, for scene objects (vegetation/objects.h).
struct ObjectModel {
    std::string path;
    std::vector<ModelNode> nodes;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f}; // model frame (Z-up) bounds of every triangle vertex
    // Index of the first node named `name`, or -1.
    int findNode(const std::string& name) const;
    size_t triangleCount() const;
};

// Loads the default scene's node hierarchy (no scene: every mesh as an unnamed root node). Same file errors as
// loadGltfMesh, plus: base colour textures are ignored (the factor is used), node names are kept as they are.
ObjectModel loadGltfModel(const std::string& path, const AssetPolicy& assets = {});

} // namespace sward
