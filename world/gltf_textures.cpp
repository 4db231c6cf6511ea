#include "world/gltf_textures.h"

#include "common/error.h"
#include "io/image_io.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cstring>
#include <filesystem>

namespace sward {

namespace {

bool isPng(const unsigned char* bytes, int size) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return size >= 8 && std::memcmp(bytes, signature, 8) == 0;
}

// glTF uris are percent-encoded (RFC 3986): "my%20grass.png".
std::string percentDecoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
            std::isxdigit((unsigned char)uri[i + 2])) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// PNG bytes as a ground texture, at most kMaxGroundTextureEdge per edge (checked from the header, before a pixel
// is decoded); `name` names them in errors.
GroundTexture decodeTexture(const std::string& name, const std::vector<char>& bytes) {
    GroundTexture texture;
    texture.rgba = decodePngRgba8(name, bytes, kMaxGroundTextureEdge, texture.width, texture.height);
    return texture;
}

} // namespace

bool decodeGltfImage(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                     int size, void*) {
    // Kept as PNG bytes: groundTexture decodes only the images a material uses, each once (decoding every embedded
    // image here cost 256 MiB an 8192^2 image, used or not).
    if (!isPng(bytes, size)) return true; // refused later, and only if a ground material uses it
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

GroundTexture groundTexture(const tinygltf::Model& model, int textureIndex, const std::string& what,
                            const AssetPolicy& assets, const std::string& gltfPath) {
    require(textureIndex >= 0 && size_t(textureIndex) < model.textures.size(),
            what + ": a material's baseColorTexture refers to a missing texture");
    const int source = model.textures[size_t(textureIndex)].source;
    require(source >= 0 && size_t(source) < model.images.size(),
            what + ": texture " + std::to_string(textureIndex) + " has no image");
    const tinygltf::Image& image = model.images[size_t(source)];
    const std::string notPng = what + ": image " + std::to_string(source) +
                               " is not a PNG (ground textures are read from PNG only; export PNG images)";
    if (image.as_is && !image.image.empty())
        return decodeTexture(gltfPath + " image " + std::to_string(source),
                             std::vector<char>(image.image.begin(), image.image.end()));
    require(!image.uri.empty() && image.uri.rfind("data:", 0) != 0, notPng);
    const std::string folder = std::filesystem::path(gltfPath).parent_path().string();
    const std::string path =
        assets.resolve(percentDecoded(image.uri), folder, what + ": image " + std::to_string(source) + " uri");
    const std::vector<char> bytes = readImageFileBytes(path);
    assets.folders().record(gltfPath, std::filesystem::weakly_canonical(path).string());
    require(isPng(reinterpret_cast<const unsigned char*>(bytes.data()), int(std::min<size_t>(bytes.size(), 8))), notPng);
    return decodeTexture(path, bytes);
}

} // namespace sward
