// Dataset fingerprints: differences named as the command line words them, and keys left out not compared.
#include "dataset/fingerprint.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "io/raster_file.h"
#include "scene/scene.h"
#include "world/gltf_mesh.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

using namespace sward;

namespace {

nlohmann::json sample() {
    return {{"scene_sha256", "ab12"},
            {"assets", {{"grass_map", "cd34"}}},
            {"seed", 5},
            {"resolution", "160x120"},
            {"samples", 4},
            {"no_vegetation", false},
            {"time", 0.0},
            {"camera", nullptr},
            {"device", "llvmpipe"}};
}

} // namespace

TEST(Fingerprint, EqualFingerprintsHaveNoDifference) {
    EXPECT_EQ(fingerprintDifference(sample(), sample()), "");
}

TEST(Fingerprint, DifferencesAreWordedAsTheCommandLine) {
    nlohmann::json other = sample();
    other["resolution"] = "200x150";
    EXPECT_EQ(fingerprintDifference(sample(), other),
              "was rendered with --resolution 160x120, this run asks for --resolution 200x150");
    other = sample();
    other["no_vegetation"] = true;
    EXPECT_EQ(fingerprintDifference(sample(), other),
              "was rendered with vegetation, this run asks for --no-vegetation");
    other = sample();
    other["camera"] = {1.0, 2.5, 3.0};
    EXPECT_EQ(fingerprintDifference(sample(), other),
              "was rendered with the scene's camera position, this run asks for --camera 1.0,2.5,3.0");
}

TEST(Fingerprint, AChangedOrRemovedAssetIsADifference) {
    nlohmann::json other = sample();
    other["assets"]["grass_map"] = "ef56";
    EXPECT_NE(fingerprintDifference(sample(), other).find("asset 'grass_map'"), std::string::npos);
    other["assets"] = nlohmann::json::object();
    EXPECT_NE(fingerprintDifference(sample(), other).find("asset 'grass_map'"), std::string::npos);
}

TEST(Fingerprint, AnEpisodeIsNeverContinuedBySwardRender) {
    nlohmann::json episode = sample();
    episode["episode"] = true; // render/episode_recorder.h
    EXPECT_EQ(fingerprintDifference(episode, sample()),
              "was rendered with frames a program drove (an episode Simulator.record wrote), this run asks for the "
              "scene's own sequence");
    EXPECT_EQ(fingerprintDifference(episode, episode), "");
}

TEST(Fingerprint, KeysLeftOutOfTheWantedFingerprintAreNotCompared) {
    nlohmann::json withoutDevice = sample();
    withoutDevice.erase("device");
    EXPECT_EQ(fingerprintDifference(sample(), withoutDevice), "");
    nlohmann::json otherDevice = sample();
    otherDevice["device"] = "RTX";
    EXPECT_EQ(fingerprintDifference(sample(), otherDevice),
              "was rendered with device 'llvmpipe', this run asks for device 'RTX'");
}

TEST(Fingerprint, DatasetFileRoundTripsAndForeignFilesAreRefused) {
    const auto dir = std::filesystem::temp_directory_path() / "sward_dataset_tests_fingerprint";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    writeTextAtomically((dir / "dataset.json").string(), datasetFileText(sample()));
    EXPECT_EQ(readDatasetFingerprint((dir / "dataset.json").string()), sample());
    writeTextAtomically((dir / "other.json").string(), R"({"name": "not a dataset"})");
    EXPECT_THROW(readDatasetFingerprint((dir / "other.json").string()), Error);
}

// A one-triangle glTF whose buffer is the file "rover mesh.bin", with `images` (uris) that no material uses.
std::string triangleGltf(const std::string& images) {
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"uri": "rover%20mesh.bin", "byteLength": 44}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
        "images": [)" +
           images + "]}";
}

std::string triangleBuffer() {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[4] = {0, 1, 2, 0};
    std::string bytes(reinterpret_cast<const char*>(positions), sizeof(positions));
    bytes.append(reinterpret_cast<const char*>(indices), sizeof(indices));
    return bytes;
}

// The fingerprint lists the files the loaders opened through the input door, not what a second parse of the glTF
// names: an image no loader reads (an object model's images, "../../../../etc/passwd") is neither read nor hashed.
TEST(Fingerprint, SceneAssetsListTheFilesTheLoadersOpenedRelativeToTheScene) {
    const std::filesystem::path dir = std::filesystem::canonical(std::filesystem::temp_directory_path()) /
                                      ("sward-assets-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "models");
    writeTextAtomically((dir / "map.png").string(), "not really a png");
    writeTextAtomically(
        (dir / "models/rover.gltf").string(),
        triangleGltf(R"({"uri": "paint.png"}, {"uri": "../../../../etc/passwd"}, {"uri": "/etc/passwd"})"));
    writeTextAtomically((dir / "models/rover mesh.bin").string(), triangleBuffer());
    writeTextAtomically((dir / "models/paint.png").string(), "paint");
    Scene scene;
    scene.assets = AssetPolicy::confinedTo(dir.string(), {});
    scene.grassMapPath = (dir / "map.png").string();
    scene.objects.push_back(ObjectParams{.model = (dir / "models/rover.gltf").string()});
    scene.objects[0].assets = scene.assets; // as parseObjects gives it: one log
    loadGltfModel(scene.objects[0].model, scene.objects[0].assets);
    const std::vector<SceneAsset> assets = sceneAssets(scene);
    std::vector<std::string> keys;
    for (const SceneAsset& a : assets) keys.push_back(a.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"grass_map", "objects[0].model", "objects[0].model/rover mesh.bin"}));
    // The same file as a ground mesh: its images no material uses are not read either.
    scene.terrain.meshPath = scene.objects[0].model;
    loadGltfMesh(scene.terrain.meshPath, scene.assets);
    keys.clear();
    for (const SceneAsset& a : sceneAssets(scene)) keys.push_back(a.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"grass_map", "terrain.mesh.file", "terrain.mesh.file/rover mesh.bin",
                                              "objects[0].model", "objects[0].model/rover mesh.bin"}));
    const nlohmann::json manifest = assetManifest(assets, dir.string());
    EXPECT_EQ(manifest.at("objects[0].model/rover mesh.bin").at("path"), "models/rover mesh.bin");
    EXPECT_EQ(manifest.at("grass_map").at("sha256"), assetHashes(assets).at("grass_map"));
    EXPECT_EQ(manifest.at("grass_map").at("sha256").get<std::string>().size(), 64u);
    std::filesystem::remove_all(dir);
}

// A companion file GDAL opened beside a raster (PAM's .aux.xml) is part of the fingerprint, so one added between
// two runs changes it and a resume refuses.
TEST(Fingerprint, ARastersCompanionFileGdalOpenedIsHashed) {
    SWARD_SKIP_WITHOUT(Gdal);
    const std::filesystem::path dir = std::filesystem::canonical(std::filesystem::temp_directory_path()) /
                                      ("sward-raster-assets-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string grid = (dir / "cover.asc").string();
    writeTextAtomically(grid, "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 10\n10 30\n");
    Scene scene;
    scene.assets = AssetPolicy::confinedTo(dir.string(), {});
    scene.landCover.file = grid;
    readRasterBand(grid, {.band = 1, .requireFinite = false, .folders = scene.assets.folders()});
    const nlohmann::json before = assetHashes(sceneAssets(scene));
    writeTextAtomically(grid + ".aux.xml", "<PAMDataset><Metadata><MDI key=\"k\">v</MDI></Metadata></PAMDataset>\n");
    readRasterBand(grid, {.band = 1, .requireFinite = false, .folders = scene.assets.folders()});
    const nlohmann::json after = assetHashes(sceneAssets(scene));
    EXPECT_FALSE(before.contains("land_cover.file/cover.asc.aux.xml")) << before.dump();
    EXPECT_TRUE(after.contains("land_cover.file/cover.asc.aux.xml")) << after.dump();
    EXPECT_NE(fingerprintDifference(before, after), "");
    std::filesystem::remove_all(dir);
}
