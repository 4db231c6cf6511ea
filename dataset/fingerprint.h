// A dataset's fingerprint: everything that determines its bytes (scene and asset hashes, seed, every render
// option, sward revision, device and driver), as one JSON object. sward-render records it in dataset.json before
// the first frame and in the manifest, and refuses to add frames to a folder whose fingerprint differs, so a
// resumed or sharded run never mixes files of two different renders. Which frames a run renders (--frames,
// --shard) is not part of it: shards of one dataset share it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sward {

struct Scene;

// One file a scene read: `key` names where the scene names it ("grass_map", "objects[0].model", and
// "objects[0].model/<uri>" for a buffer or image a .gltf names), `path` is the file as opened.
struct SceneAsset {
    std::string key, path, sha256;
};
// Every asset file of `scene` that exists, hashed (SHA-256), in a fixed order: grass map, land-cover raster, atlas
// PNG and JSON, terrain heightmap, terrain mesh, object models; after each, the other files its loader opened
// through the input door (scene.assets.folders()'s log: a glTF's buffers and images, a raster's companion files
// such as "terrain.heightmap.file/dem.tif.aux.xml"), named relative to its folder. Call after the scene's assets
// were loaded (buildSceneResources); nothing outside what the loaders read is read.
std::vector<SceneAsset> sceneAssets(const Scene& scene);
// The fingerprint's "assets": {key: sha256}.
nlohmann::json assetHashes(const std::vector<SceneAsset>& assets);
// The manifest's "assets": {key: {"path": path relative to `sceneDir` (the scene file's folder), "sha256"}}, so
// a dataset names every input it needs beside its copy of the scene file.
nlohmann::json assetManifest(const std::vector<SceneAsset>& assets, const std::string& sceneDir);

// The content of dataset.json for `fingerprint`: {"format": "sward-dataset-1", "fingerprint": {...}}.
std::string datasetFileText(const nlohmann::json& fingerprint);
// The fingerprint recorded in the dataset.json at `path`; throws a clear error when it is not one sward wrote.
nlohmann::json readDatasetFingerprint(const std::string& path);

// "" when `recorded` agrees with `wanted`, else the first difference as "was rendered with X, this run asks for
// Y", X and Y worded as the command line or scene gives them ("--resolution 160x120", "--no-vegetation"). Keys
// absent from `wanted` are not compared (a check before the device is known leaves out "device" and "driver").
std::string fingerprintDifference(const nlohmann::json& recorded, const nlohmann::json& wanted);

} // namespace sward
