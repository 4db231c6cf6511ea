#include "dataset/fingerprint.h"

#include "common/error.h"
#include "io/sha256.h"
#include "scene/scene.h"

#include <filesystem>
#include <fstream>
#include <cctype>
#include <map>
#include <sstream>

namespace sward {

namespace {

constexpr const char* kFormat = "sward-dataset-1";

std::string vec3Text(const nlohmann::json& v) {
    std::string text;
    for (const nlohmann::json& x : v) text += (text.empty() ? "" : ",") + x.dump();
    return text;
}

// How the command line or the scene words the value `value` of fingerprint key `key`.
std::string describe(const std::string& key, const nlohmann::json& value) {
    if (value.is_null()) {
        if (key == "camera") return "the scene's camera position";
        if (key == "look_at") return "the scene's camera target";
        if (key == "fov_y_deg") return "the scene's field of view";
        return "no " + key;
    }
    if (key == "resolution") return "--resolution " + value.get<std::string>();
    if (key == "samples") return "--samples " + value.dump();
    if (key == "no_vegetation") return value.get<bool>() ? "--no-vegetation" : "vegetation";
    if (key == "time") return "--time " + value.dump();
    if (key == "seed") return "seed " + value.dump();
    if (key == "camera") return "--camera " + vec3Text(value);
    if (key == "look_at") return "--look-at " + vec3Text(value);
    if (key == "fov_y_deg") return "--fov " + value.dump();
    if (key == "scene_sha256") return "a scene file of SHA-256 " + value.get<std::string>().substr(0, 12) + "...";
    if (key.starts_with("assets."))
        return "asset '" + key.substr(7) + "' of SHA-256 " + value.get<std::string>().substr(0, 12) + "...";
    if (key == "sward_revision") return "sward revision " + value.get<std::string>();
    if (key == "device") return "device '" + value.get<std::string>() + "'";
    if (key == "driver") return "driver '" + value.get<std::string>() + "'";
    return key + " " + value.dump();
}

// {"assets": {"grass_map": h}} -> {"assets.grass_map": h}: one level of nesting, as the fingerprint has.
std::map<std::string, nlohmann::json> flatten(const nlohmann::json& json) {
    std::map<std::string, nlohmann::json> flat;
    for (const auto& [key, value] : json.items()) {
        if (!value.is_object()) {
            flat[key] = value;
            continue;
        }
        for (const auto& [inner, innerValue] : value.items()) flat[key + "." + inner] = innerValue;
    }
    return flat;
}

// "a%20b.bin" -> "a b.bin": glTF URIs are percent-encoded.
std::string percentDecoded(const std::string& uri) {
    std::string text;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
            std::isxdigit(uint8_t(uri[i + 2]))) {
            text += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            text += uri[i];
        }
    }
    return text;
}

// The files a .gltf names (buffers and images that are not data: URIs), relative to its folder. A .glb holds its
// own buffers; a file the parser cannot read adds nothing (the loader has already accepted it).
std::vector<std::string> gltfExternalFiles(const std::string& path) {
    std::vector<std::string> files;
    if (!path.ends_with(".gltf")) return files;
    std::ifstream file(path, std::ios::binary);
    const nlohmann::json json = nlohmann::json::parse(file, nullptr, false);
    if (!json.is_object()) return files;
    for (const char* list : {"buffers", "images"}) {
        if (!json.contains(list) || !json[list].is_array()) continue;
        for (const nlohmann::json& item : json[list])
            if (item.is_object() && item.contains("uri") && item["uri"].is_string() &&
                !item["uri"].get<std::string>().starts_with("data:"))
                files.push_back(percentDecoded(item["uri"].get<std::string>()));
    }
    return files;
}

} // namespace

std::vector<SceneAsset> sceneAssets(const Scene& scene) {
    std::vector<SceneAsset> assets;
    auto add = [&](const std::string& key, const std::string& path) {
        std::error_code ec;
        if (path.empty() || !std::filesystem::is_regular_file(path, ec)) return;
        assets.push_back({key, path, sha256File(path)});
        const std::filesystem::path folder = std::filesystem::path(path).parent_path();
        for (const std::string& uri : gltfExternalFiles(path)) {
            const std::string file = (folder / uri).string();
            if (std::filesystem::is_regular_file(file, ec)) assets.push_back({key + "/" + uri, file, sha256File(file)});
        }
    };
    add("grass_map", scene.grassMapPath);
    add("land_cover.file", scene.landCover.file);
    add("atlas.png", scene.atlasPngPath);
    add("atlas.json", scene.atlasJsonPath);
    add("terrain.heightmap.file", scene.terrain.heightmap.path);
    add("terrain.mesh.file", scene.terrain.meshPath);
    for (size_t k = 0; k < scene.objects.size(); ++k)
        add("objects[" + std::to_string(k) + "].model", scene.objects[k].model);
    return assets;
}

nlohmann::json assetHashes(const std::vector<SceneAsset>& assets) {
    nlohmann::json hashes = nlohmann::json::object();
    for (const SceneAsset& asset : assets) hashes[asset.key] = asset.sha256;
    return hashes;
}

nlohmann::json assetManifest(const std::vector<SceneAsset>& assets, const std::string& sceneDir) {
    nlohmann::json manifest = nlohmann::json::object();
    for (const SceneAsset& asset : assets) {
        std::error_code ec;
        std::filesystem::path relative = std::filesystem::relative(asset.path, sceneDir.empty() ? "." : sceneDir, ec);
        if (ec || relative.empty()) relative = asset.path;
        manifest[asset.key] = {{"path", relative.generic_string()}, {"sha256", asset.sha256}};
    }
    return manifest;
}

std::string datasetFileText(const nlohmann::json& fingerprint) {
    return nlohmann::json{{"format", kFormat}, {"fingerprint", fingerprint}}.dump(2) + "\n";
}

nlohmann::json readDatasetFingerprint(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    require(bool(file), "cannot read '" + path + "'");
    std::stringstream text;
    text << file.rdbuf();
    const nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, false);
    require(json.is_object() && json.value("format", "") == kFormat && json.contains("fingerprint") &&
                json["fingerprint"].is_object(),
            "'" + path + "' is not a sward dataset description (expected {\"format\": \"" + kFormat +
                "\", \"fingerprint\": {...}})");
    return json["fingerprint"];
}

std::string fingerprintDifference(const nlohmann::json& recorded, const nlohmann::json& wanted) {
    const std::map<std::string, nlohmann::json> old = flatten(recorded), now = flatten(wanted);
    auto differs = [](const std::string& key, const nlohmann::json& a, const nlohmann::json& b) {
        return "was rendered with " + describe(key, a) + ", this run asks for " + describe(key, b);
    };
    for (const auto& [key, value] : now) {
        auto it = old.find(key);
        if (it == old.end() || it->second != value) return differs(key, it == old.end() ? nullptr : it->second, value);
    }
    for (const auto& [key, value] : old) // an asset the old dataset had and this scene has not
        if (!now.contains(key) && key.find('.') != std::string::npos && wanted.contains(key.substr(0, key.find('.'))))
            return differs(key, value, nullptr);
    return "";
}

} // namespace sward
