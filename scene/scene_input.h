// SceneInput: where a scene comes from when a program, not a command line, names it (the Python module, and
// sward-render through the same function): a file or JSON text, plus overrides of any key, applied before parsing.
#pragma once

#include "scene/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sward {

struct SceneInput {
    std::string path;                       // scene file; "" = built-in defaults (unless `text`)
    std::optional<std::string> text;        // the scene as JSON text instead of a file (named "<scene>" in errors)
    std::string overrides;                  // JSON object of dotted keys -> values, e.g. {"render.samples": 1}
    std::optional<uint64_t> seed;           // replaces the scene's seed (after the overrides)
    std::vector<std::string> allowedAssetDirs; // besides a scene file's folder (--allow-assets)
};

// Reads the JSON (loadScene's checks for a file), replaces or adds each overridden key ("vehicles.0.weight": array
// elements by index; missing objects are created), then parses it like loadScene: a file's assets confined to its
// folder and `allowedAssetDirs`, text and the built-in scene unconfined. Errors name the file or "<scene>" and the
// key, e.g. "overrides: 'render.samples.x' goes through a value that is not an object".
Scene loadSceneInput(const SceneInput& input);

// The JSON document loadSceneInput parses (overrides and seed applied): what a dataset's fingerprint hashes.
nlohmann::json sceneInputJson(const SceneInput& input);

} // namespace sward
