// A glTF or GLB file read with tinygltf through sward's input door (common/input_file.h): tinygltf opens the file
// and every buffer a .gltf names through callbacks that resolve each name with the scene's AssetPolicy (symlinks
// followed), refuse a file that is not regular (a FIFO never blocks), and log each file in assets.folders() with
// the glTF's path as owner, for the dataset's fingerprint. Images are not read here: tinygltf is built without
// external images, and a ground's textures are read by world/gltf_textures.h.
#pragma once

#include "world/asset_policy.h"

#include <string>

namespace tinygltf {
class Model;
} // namespace tinygltf

namespace sward {

// Parses `path` (".glb" by its extension, else ".gltf"); `kind` names it in errors ("glTF ground"). decodeImages:
// embedded PNG images become RGBA (ground meshes draw their base-colour textures); else they are skipped (object
// models use factors only). Throws one sward::Error naming the file for a refused or unreadable file, a
// required extension sward lacks (Draco), a buffer of the wrong size and any parse error (on one line).
tinygltf::Model readGltfFile(const std::string& path, const char* kind, const AssetPolicy& assets, bool decodeImages);

} // namespace sward
