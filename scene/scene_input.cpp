#include "scene/scene_input.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "world/asset_policy.h"

#include <filesystem>

namespace sward {

namespace {

// The JSON value `dotted` ("render.resolution", "objects.0.model") names in `document`, created when absent.
nlohmann::json& overriddenValue(nlohmann::json& document, const std::string& dotted) {
    require(!dotted.empty(), "overrides: an empty key");
    nlohmann::json* node = &document;
    size_t begin = 0;
    while (true) {
        const size_t end = dotted.find('.', begin);
        const std::string part = dotted.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
        require(!part.empty(), "overrides: '" + dotted + "' has an empty part");
        if (node->is_array()) {
            const bool digits = part.find_first_not_of("0123456789") == std::string::npos && part.size() < 10;
            require(digits && std::stoul(part) < node->size(),
                    "overrides: '" + dotted + "': '" + part + "' is not an index of an array of " +
                        std::to_string(node->size()));
            node = &(*node)[std::stoul(part)];
        } else {
            require(node->is_object() || node->is_null(),
                    "overrides: '" + dotted + "' goes through a value that is not an object");
            node = &(*node)[part];
        }
        if (end == std::string::npos) return *node;
        begin = end + 1;
    }
}

} // namespace

nlohmann::json sceneInputJson(const SceneInput& input) {
    nlohmann::json document = nlohmann::json::object();
    if (input.text)
        document = parseJsonText(*input.text, "<scene>", "scene");
    else if (!input.path.empty())
        document = readJsonFile(input.path, "scene file");
    if (!input.overrides.empty()) {
        const nlohmann::json overrides = parseJsonText(input.overrides, "overrides", "overrides");
        require(overrides.is_object(), "overrides: must be an object of dotted keys");
        require(document.is_object(), (input.text ? std::string("<scene>") : input.path) + ": must be a JSON object");
        for (const auto& [key, value] : overrides.items()) overriddenValue(document, key) = value;
    }
    if (input.seed && document.is_object()) document["seed"] = *input.seed; // every seed derived from it follows
    return document;
}

Scene loadSceneInput(const SceneInput& input) {
    const nlohmann::json document = sceneInputJson(input);
    if (input.text) return parseScene(document, "<scene>");
    if (input.path.empty()) return parseScene(document, "<built-in>");
    // A scene file's assets stay inside its folder and the folders the user allows.
    return parseScene(document, input.path,
                      AssetPolicy::confinedTo(std::filesystem::path(input.path).parent_path().string(),
                                              input.allowedAssetDirs));
}

} // namespace sward
