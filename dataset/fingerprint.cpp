#include "dataset/fingerprint.h"

#include "common/error.h"
#include "common/input_file.h"
#include "io/sha256.h"
#include "scene/scene.h"

#include <cctype>
#include <filesystem>
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
        if (key == "episode") return "the scene's own sequence";
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
    if (key == "episode") return "frames a program drove (an episode Simulator.record wrote)";
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

} // namespace

std::vector<SceneAsset> sceneAssets(const Scene& scene) {
    namespace fs = std::filesystem;
    // What the loaders opened through the input door for each asset (its buffers, images and companion files),
    // owner by owner; nothing is parsed again here, so nothing the loaders did not read is read.
    const std::vector<OpenedInput> opened = scene.assets.folders().opened();
    std::vector<SceneAsset> assets;
    auto add = [&](const std::string& key, const std::string& path) {
        std::error_code ec;
        if (path.empty() || !fs::is_regular_file(path, ec)) return;
        assets.push_back({key, path, sha256File(path)});
        const fs::path real = fs::weakly_canonical(path, ec);
        for (const OpenedInput& file : opened) {
            if (file.owner != path || file.path == real) continue;
            const std::string name = fs::path(file.path).lexically_relative(real.parent_path()).generic_string();
            assets.push_back({key + "/" + name, file.path, sha256File(file.path)});
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
    const nlohmann::json json = nlohmann::json::parse(readInputFile(path, "dataset description"), nullptr, false);
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
    // An asset the old dataset had and this scene has not; an episode a program recorded (render/episode_recorder.h),
    // which no sward-render run continues.
    for (const auto& [key, value] : old)
        if (!now.contains(key) &&
            ((key.find('.') != std::string::npos && wanted.contains(key.substr(0, key.find('.')))) || key == "episode"))
            return differs(key, value, nullptr);
    return "";
}

} // namespace sward
