// Dataset naming: the file names and class table the writer and the evaluation share.
#include "dataset/naming.h"

#include "shared/gpu_layout.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

using namespace sward;

TEST(DatasetNaming, FrameNamesAreSixDigitsZeroPadded) {
    EXPECT_EQ(frameName(0), "000000");
    EXPECT_EQ(frameName(42), "000042");
    EXPECT_EQ(frameName(999999), "999999");
}

TEST(DatasetNaming, FrameNumberReadsBackExactlySixDigits) {
    for (uint32_t frame : {0u, 7u, 42u, 123456u, 999999u}) EXPECT_EQ(frameNumber(frameName(frame)), frame);
    for (const char* stem : {"", "42", "0000042", "00004x", "-00042", " 00042", "000042.png"})
        EXPECT_FALSE(frameNumber(stem).has_value()) << "'" << stem << "'";
}

TEST(DatasetNaming, FrameFilesAreFolderSlashNameExtension) {
    EXPECT_EQ(frameFile(kLeftFolder, 42, ".exr"), "left/000042.exr");
    EXPECT_EQ(frameFile(kDisparityFolder, 3, ".pfm"), "disparity/000003.pfm");
    EXPECT_EQ(frameFile(kPreviewRightFolder, 1, ".png"), "preview_right/000001.png");
}

TEST(DatasetNaming, ShardManifestsNameTheirShard) {
    EXPECT_EQ(shardManifestName(0, 4), "manifest.shard-0-of-4.json");
    EXPECT_STREQ(kManifestFile, "manifest.json");
}

TEST(DatasetNaming, ClassTableFollowsTheGpuNumbers) {
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticSky)->name, "sky");
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticGround)->name, "ground");
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticObject)->name, "object");
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticFelled)->name, "felled");
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticCut)->name, "cut");
    EXPECT_STREQ(findSemanticClass(gpu::kSemanticVegetation + 1)->name, "vegetation category 1");
    EXPECT_EQ(findSemanticClass(6), nullptr);
    EXPECT_EQ(findSemanticClass(255), nullptr);
}

TEST(DatasetNaming, VegetationIsCategoriesFelledAndCut) {
    // docs/dataset-format.md: "Vegetation" is 2-5, 9 and 10.
    std::set<uint32_t> vegetation;
    for (const SemanticClass& c : semanticClasses())
        if (std::string(c.group) == "vegetation") vegetation.insert(c.id);
    EXPECT_EQ(vegetation, (std::set<uint32_t>{2, 3, 4, 5, 9, 10}));
}

TEST(DatasetNaming, ClassIdsAreUniqueAndIncreasing) {
    const std::span<const SemanticClass> classes = semanticClasses();
    ASSERT_FALSE(classes.empty());
    for (size_t i = 1; i < classes.size(); ++i) EXPECT_GT(classes[i].id, classes[i - 1].id) << classes[i].name;
    EXPECT_LT(classes.back().id, 256u) << "semantic/ PNGs hold one byte per pixel";
}

TEST(DatasetNaming, ClassesFileListsEveryClassWithColourAndTheScenesCategoryNames) {
    const std::vector<std::string> names = {"ferns", "grass"};
    const nlohmann::json file = nlohmann::json::parse(classesFileText(names));
    EXPECT_EQ(file.at("format"), "sward-classes-1");
    ASSERT_EQ(file.at("classes").size(), semanticClasses().size());
    for (size_t i = 0; i < semanticClasses().size(); ++i) {
        const nlohmann::json& c = file.at("classes")[i];
        EXPECT_EQ(c.at("id"), semanticClasses()[i].id);
        EXPECT_EQ(c.at("name"), semanticClasses()[i].name);
        EXPECT_EQ(c.at("colour").size(), 3u);
    }
    EXPECT_EQ(file.at("classes")[3].at("scene_name"), "grass"); // id 3 = category 1
    EXPECT_EQ(file.at("classes")[3].at("category"), 1);
    EXPECT_FALSE(file.at("classes")[4].contains("scene_name")); // category 2: not in this scene
}
