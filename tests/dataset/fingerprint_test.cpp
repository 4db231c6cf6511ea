// Dataset fingerprints: differences named as the command line words them, and keys left out not compared.
#include "dataset/fingerprint.h"

#include "common/atomic_file.h"
#include "common/error.h"

#include <gtest/gtest.h>

#include <filesystem>

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
