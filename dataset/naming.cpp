#include "dataset/naming.h"

#include "shared/gpu_layout.h"
#include "shared/plant_layout.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>

namespace sward {

namespace {

// Vegetation categories take the ids from kSemanticVegetation up; they must stay below the next class.
static_assert(gpu::kSemanticVegetation + gpu::kMaxPlantCategories <= gpu::kSemanticObject);

// Colours: Cityscapes' sky and vegetation greens where they fit, distinct hues for the rest.
constexpr SemanticClass kClasses[] = {
    {gpu::kSemanticSky, "sky", "sky", {70, 130, 180}},
    {gpu::kSemanticGround, "ground", "ground", {145, 110, 70}},
    {gpu::kSemanticVegetation + 0, "vegetation category 0", "vegetation", {107, 142, 35}},
    {gpu::kSemanticVegetation + 1, "vegetation category 1", "vegetation", {152, 251, 152}},
    {gpu::kSemanticVegetation + 2, "vegetation category 2", "vegetation", {220, 180, 40}},
    {gpu::kSemanticVegetation + 3, "vegetation category 3", "vegetation", {60, 110, 90}},
    {gpu::kSemanticObject, "object", "object", {220, 20, 60}},
    {gpu::kSemanticFelled, "felled", "vegetation", {170, 120, 200}},
    {gpu::kSemanticCut, "cut", "vegetation", {250, 170, 160}},
    {gpu::kSemanticTurf, "turf", "ground", {60, 160, 70}},
    {gpu::kSemanticTrack, "track", "ground", {90, 60, 40}},
};
static_assert(std::size(kClasses) == 7 + gpu::kMaxPlantCategories, "one entry per vegetation category");

} // namespace

FlowFolders flowFolders(bool right, bool forward) {
    if (forward)
        return right ? FlowFolders{kFlowForwardRightFolder, kFlowForwardMaskRightFolder}
                     : FlowFolders{kFlowForwardFolder, kFlowForwardMaskFolder};
    return right ? FlowFolders{kFlowBackwardRightFolder, kFlowBackwardMaskRightFolder}
                 : FlowFolders{kFlowBackwardFolder, kFlowBackwardMaskFolder};
}

std::string frameName(uint32_t frame) {
    char name[16];
    std::snprintf(name, sizeof name, "%06u", frame);
    return name;
}

std::optional<uint32_t> frameNumber(std::string_view stem) {
    if (stem.size() != 6 || !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return std::nullopt;
    uint32_t frame = 0;
    for (char c : stem) frame = frame * 10 + uint32_t(c - '0');
    return frame;
}

std::vector<std::string> rangeFrameFiles(const std::string& name, RangeSensorType type, uint32_t frame) {
    const std::string stem = std::string(kRangeFolder) + "/" + name + "/" + frameName(frame);
    switch (type) {
    case RangeSensorType::Lidar:
        return {stem + ".ply", stem + ".bin", stem + ".label"};
    case RangeSensorType::Scanner:
        return {stem + ".json", stem + ".ply"};
    case RangeSensorType::TimeOfFlight:
        return {stem + ".exr"};
    }
    return {};
}

std::string frameFile(const char* folder, uint32_t frame, const char* extension) {
    return std::string(folder) + "/" + frameName(frame) + extension;
}

std::string shardManifestName(uint32_t index, uint32_t count) {
    return "manifest.shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".json";
}

std::span<const SemanticClass> semanticClasses() {
    return kClasses;
}

const SemanticClass* findSemanticClass(uint32_t id) {
    for (const SemanticClass& c : kClasses)
        if (c.id == id) return &c;
    return nullptr;
}

std::string classesFileText(std::span<const std::string> categoryNames) {
    nlohmann::json classes = nlohmann::json::array();
    for (const SemanticClass& c : kClasses) {
        nlohmann::json entry = {{"id", c.id}, {"name", c.name}, {"group", c.group},
                                {"colour", {c.colour[0], c.colour[1], c.colour[2]}}};
        const uint32_t category = c.id - gpu::kSemanticVegetation;
        if (c.id >= gpu::kSemanticVegetation && category < gpu::kMaxPlantCategories) {
            entry["category"] = category;
            if (category < categoryNames.size()) entry["scene_name"] = categoryNames[category];
        }
        classes.push_back(std::move(entry));
    }
    const nlohmann::json file = {
        {"format", "sward-classes-1"},
        {"classes", classes},
        {"instances", {{"sky_and_ground", 0},
                       {"plant", "record index + 1 (1 .. " + std::to_string(gpu::kMaxPlantInstances) + ")"},
                       {"object", std::to_string(gpu::kInstanceObjectBase) + " + index in the scene's objects"}}}};
    return file.dump(2) + "\n";
}

} // namespace sward
