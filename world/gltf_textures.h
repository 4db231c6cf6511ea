// glTF base-colour textures of ground meshes (world/gltf_mesh.cpp): images decoded with sward's own PNG reader
// (io/image_io.h: sizes checked against the data before anything is allocated), never by stb_image directly.
#pragma once

#include "world/asset_policy.h"
#include "world/ground.h"

#include <string>

namespace tinygltf {
struct Image;
class Model;
} // namespace tinygltf

namespace sward {

// Largest ground texture edge, in pixels.
inline constexpr uint32_t kMaxGroundTextureEdge = 8192;
// Largest set of ground textures, as 8-bit RGBA: four textures of 8192x8192. Each image is decoded once however
// many textures and materials use it, and the set is priced as it grows.
inline constexpr uint64_t kMaxGroundTextureBytes = uint64_t(1) << 30;

// tinygltf's image callback for grounds (embedded images: data uris and buffer views; tinygltf is built without
// external image loading): a PNG's bytes are kept as they are in image->image (as_is), decoded by groundTexture
// only if a material uses them; any other format is left out (an error only if a ground material uses it).
bool decodeGltfImage(tinygltf::Image* image, int index, std::string* err, std::string* warn, int requestedWidth,
                     int requestedHeight, const unsigned char* bytes, int size, void* user);

// The image of texture `textureIndex` as a GroundTexture, decoded here: an embedded one as decodeGltfImage kept it,
// an external one (uri) read relative to the folder of `gltfPath` and only where `assets` allows, and logged
// in assets.folders() with `gltfPath` as its owner (it joins the dataset's fingerprint). Throws sward::Error naming
// `what` for an index out of range, an image that is missing, refused, not a regular file or not a PNG.
GroundTexture groundTexture(const tinygltf::Model& model, int textureIndex, const std::string& what,
                            const AssetPolicy& assets, const std::string& gltfPath);

} // namespace sward
