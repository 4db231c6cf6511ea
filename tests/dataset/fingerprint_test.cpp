// Dataset fingerprints: differences named as the command line words them, and keys left out not compared.
#include "dataset/fingerprint.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

using namespace sward;

namespace {

nlohmann::json sample() {
    return {{"scene_sha256", "ab12"}, {"assets", {{"grass_map", "cd34"}}}, {"seed", 5}, {"resolution", "160x120"},
            {"samples", 4}, {"no_vegetation", false}, {"time", 0.0}, {"camera", nullptr}, {"device", "llvmpipe"}};
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
    EXPECT_EQ(fingerprintDifference(sample(), other), "was rendered with vegetation, this run asks for --no-vegetation");
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

TEST(Fingerprint, SceneAssetsListEveryFileWithItsGltfBuffersRelativeToTheScene) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("sward-assets-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "models");
    writeTextAtomically((dir / "map.png").string(), "not really a png");
    writeTextAtomically((dir / "models/rover.gltf").string(),
                        R"({"buffers": [{"uri": "rover%20mesh.bin"}, {"uri": "data:application/octet-stream;base64,AA=="}],
                            "images": [{"uri": "paint.png"}, {"uri": "missing.png"}]})");
    writeTextAtomically((dir / "models/rover mesh.bin").string(), "bytes");
    writeTextAtomically((dir / "models/paint.png").string(), "paint");
    Scene scene;
    scene.grassMapPath = (dir / "map.png").string();
    scene.objects.push_back(ObjectParams{.model = (dir / "models/rover.gltf").string()});
    const std::vector<SceneAsset> assets = sceneAssets(scene);
    std::vector<std::string> keys;
    for (const SceneAsset& a : assets) keys.push_back(a.key);
    // Data URIs are part of the .gltf; a missing file is not hashed (the loader would have refused it).
    EXPECT_EQ(keys, (std::vector<std::string>{"grass_map", "objects[0].model", "objects[0].model/rover mesh.bin",
                                              "objects[0].model/paint.png"}));
    const nlohmann::json manifest = assetManifest(assets, dir.string());
    EXPECT_EQ(manifest.at("objects[0].model/rover mesh.bin").at("path"), "models/rover mesh.bin");
    EXPECT_EQ(manifest.at("grass_map").at("sha256"), assetHashes(assets).at("grass_map"));
    EXPECT_EQ(manifest.at("grass_map").at("sha256").get<std::string>().size(), 64u);
    std::filesystem::remove_all(dir);
}
