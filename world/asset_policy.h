// AssetPolicy: where the files a scene names (object models, the grass map, the atlas, the buffers a glTF names)
// may be read from. A scene file's assets must resolve — `..`, absolute paths and symlinks all followed first —
// inside the scene file's folder or inside a folder the user allows (--allow-assets DIR), so a scene from an
// untrusted source cannot read other files on the machine. Built-in scenes (no folder) are unconfined.
#pragma once

#include "common/input_file.h"

#include <filesystem>
#include <string>
#include <vector>

namespace sward {

class AssetPolicy {
public:
    // Unconfined: every path is accepted as it is (built-in scenes, files named on the command line).
    AssetPolicy() = default;
    // Confined to `folder` (the scene file's folder; "" = the current directory) and the `allowed` folders.
    // Throws sward::Error "--allow-assets 'DIR': ..." when an allowed folder does not exist.
    static AssetPolicy confinedTo(const std::string& folder, const std::vector<std::string>& allowed);

    bool confined() const { return folders_.confined(); }
    // The folders as the input door (common/input_file.h) takes them, with the log of every file read on this
    // policy's behalf (copies of a policy share it): rasters pass them to GDAL's door, glTF loaders record
    // their buffers and images, and the dataset fingerprint lists what was logged.
    const InputFolders& folders() const { return folders_; }

    // The path to open for `path` as named by `where` (e.g. "scene.json: 'objects[0].model'"). A relative path
    // is taken relative to `base` (a folder; "" = the current directory). Confined: returns the resolved path
    // (symlinks followed), or throws sward::Error "<where>: '<path>' resolves to R, outside the scene's folder F
    // (allow with --allow-assets DIR)"; unconfined: returns base / path unchanged otherwise.
    std::string resolve(const std::string& path, const std::string& base, const std::string& where) const;

private:
    std::filesystem::path folder_; // canonical, for messages
    InputFolders folders_;         // the scene's folder and the allowed ones
};

} // namespace sward
