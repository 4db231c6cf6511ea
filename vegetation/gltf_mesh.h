// Ground meshes from glTF 2.0 files (tinygltf).
#pragma once

#include "ground.h"

#include <string>

namespace sward {

// Loads every triangle primitive reachable from the default scene of a .gltf (embedded or external buffers) or
// .glb file, with node transforms applied and glTF's Y-up converted to sward's Z-up: (x, y, z) -> (x, -z, y).
// Throws sward::Error naming the file for a missing or malformed file, out-of-range accessors, strip/fan
// primitives, sparse accessors, or a file without triangles. Points and lines are ignored.
TriangleMesh loadGltfMesh(const std::string& path);

} // namespace sward
