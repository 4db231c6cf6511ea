#include "world/gltf_files.h"

#include "common/error.h"
#include "common/input_file.h"
#include "world/gltf_textures.h"

// The configuration of tinygltf's implementation in world/gltf_mesh.cpp: the class layout and the loader's default
// callbacks depend on it.
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <filesystem>

namespace sward {

namespace {

// Object models need no textures: skip decoding their images entirely.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf opens the files a glTF's buffers name through these callbacks, so each one is checked against the
// asset policy (symlinks resolved) before a byte of it is read.
struct BufferFiles {
    const AssetPolicy& assets;
    std::string gltfPath; // the glTF file, owner of every file read for it in the policy's log
    std::string where;    // "glTF model 'm.gltf': buffer uri", for the policy's error
    std::string joinedTo; // what tinygltf puts before "/<uri>": the glTF path up to its last separator
    std::string folder;   // the glTF's folder, which a relative uri is relative to
    std::string refused;  // the policy's error, once it refused a file
    std::string lastUri;  // the last buffer file read (tinygltf then compares its size with byteLength)

    // The uri tinygltf joined into `path`; "" for its fallback to the current directory (a relative uri is
    // relative to the glTF's folder only).
    std::string uriOf(const std::string& path) const {
        if (joinedTo.empty()) return path;
        const size_t skip = joinedTo.size() + (joinedTo.back() == '/' ? 0 : 1);
        if (path.size() <= skip || path.compare(0, joinedTo.size(), joinedTo) != 0) return {};
        return path.substr(skip);
    }
};

bool bufferFileExists(const std::string& path, void* user) {
    const BufferFiles& files = *static_cast<const BufferFiles*>(user);
    const std::string uri = files.uriOf(path);
    std::error_code error;
    return !uri.empty() && std::filesystem::exists(std::filesystem::path(files.folder) / uri, error);
}

std::string keepPath(const std::string& path, void*) {
    return path;
}

bool readBufferFile(std::vector<unsigned char>* out, std::string*, const std::string& path, void* user) {
    BufferFiles& files = *static_cast<BufferFiles*>(user);
    std::string opened;
    try {
        opened = files.assets.resolve(files.uriOf(path), files.folder, files.where);
    } catch (const Error& e) {
        files.refused = e.what();
        return false;
    }
    files.lastUri = files.uriOf(path);
    try {
        // The door: a FIFO never blocks, a device is refused; what is read is logged for the fingerprint.
        const std::string what = path == files.gltfPath ? "glTF file" : "buffer file of '" + files.gltfPath + "'";
        *out = readInputBytes(opened, what);
        // tinygltf takes the first byte of what it is given (an empty .glb threw std::out_of_range from it), and its
        // own reader refused an empty file: so does this one.
        if (out->empty()) throw Error(opened + ": the " + what + " is empty");
        files.assets.folders().record(files.gltfPath, std::filesystem::weakly_canonical(opened).string());
        return true;
    } catch (const Error& e) {
        files.refused = e.what();
        return false;
    }
}

bool writeNothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
    return false;
}

// glTF's extensionsRequired: a file that needs an extension cannot be read correctly without it.
void checkRequiredExtensions(const tinygltf::Model& model, const std::string& what) {
    for (const std::string& name : model.extensionsRequired) {
        if (name == "KHR_draco_mesh_compression")
            throw Error(what + ": uses KHR_draco_mesh_compression, which sward does not support; export without "
                               "Draco compression");
        throw Error(what + ": uses " + name + " (extensionsRequired), which sward does not support; export without it");
    }
}

// A data: URI quoted whole (tinygltf's "Failed to decode 'uri' : data:...", a uri the asset policy refuses) would
// put up to megabytes of base64 on the error line: keep its scheme and media type and a few bytes of its data.
std::string shortenedDataUris(std::string text) {
    constexpr size_t kDataKept = 8;
    for (size_t at = text.find("data:"); at != std::string::npos; at = text.find("data:", at + 5)) {
        const size_t end = std::min(text.find_first_of(" \t\n'\"", at), text.size());
        const size_t comma = text.find(',', at);
        const size_t keep = comma < end ? comma + 1 + kDataKept : at + 40;
        if (keep + 3 >= end) continue;
        text.replace(keep, end - keep, "... (" + std::to_string(end - at) + " characters)");
    }
    return text;
}

// tinygltf's error text, on one line.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    for (char& c : text)
        if (c == '\n') c = ';';
    return text.empty() ? "unknown error" : shortenedDataUris(text);
}

} // namespace

tinygltf::Model readGltfFile(const std::string& path, const char* kind, const AssetPolicy& assets, bool decodeImages) {
    const std::string what = std::string(kind) + " '" + path + "'";
    const size_t slash = path.find_last_of("/\\"); // tinygltf's own split (GetBaseDir)
    BufferFiles files{.assets = assets,
                      .gltfPath = path,
                      .where = what + ": buffer uri",
                      .joinedTo = slash == std::string::npos ? std::string() : path.substr(0, slash),
                      .folder = std::filesystem::path(path).parent_path().string(),
                      .refused = {},
                      .lastUri = {}};
    tinygltf::TinyGLTF loader;
    if (decodeImages)
        loader.SetImageLoader(decodeGltfImage, const_cast<std::string*>(&path));
    else
        loader.SetImageLoader(ignoreImage, nullptr);
    loader.SetFsCallbacks({.FileExists = bufferFileExists,
                           .ExpandFilePath = keepPath,
                           .ReadWholeFile = readBufferFile,
                           .WriteWholeFile = writeNothing,
                           .user_data = &files});
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                             path.compare(path.size() - 4, 4, ".GLB") == 0);
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!files.refused.empty()) throw Error(shortenedDataUris(files.refused));
    // Before tinygltf's own complaint: a Draco file fails there with "accessor[0] invalid bufferView".
    checkRequiredExtensions(model, what);
    // tinygltf's size-mismatch text states the file's size: never quote a buffer file, it may be any file.
    if (!ok && err.find("File size mismatch") != std::string::npos)
        throw Error(what + ": the file of buffer uri '" + files.lastUri + "' is not byteLength bytes long");
    require(ok, "cannot load " + what + ": " + oneLine(err));
    return model;
}

} // namespace sward
