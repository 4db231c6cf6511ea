#include "dataset/naming.h"

#include "shared/gpu_layout.h"
#include "shared/plant_layout.h"

#include <algorithm>
#include <cstdio>

namespace sward {

namespace {

// Vegetation categories take the ids from kSemanticVegetation up; they must stay below the next class.
static_assert(gpu::kSemanticVegetation + gpu::kMaxPlantCategories <= gpu::kSemanticObject);

constexpr SemanticClass kClasses[] = {
    {gpu::kSemanticSky, "sky", "sky"},
    {gpu::kSemanticGround, "ground", "ground"},
    {gpu::kSemanticVegetation + 0, "vegetation category 0", "vegetation"},
    {gpu::kSemanticVegetation + 1, "vegetation category 1", "vegetation"},
    {gpu::kSemanticVegetation + 2, "vegetation category 2", "vegetation"},
    {gpu::kSemanticVegetation + 3, "vegetation category 3", "vegetation"},
    {gpu::kSemanticObject, "object", "object"},
    {gpu::kSemanticFelled, "felled", "vegetation"},
    {gpu::kSemanticCut, "cut", "vegetation"},
};
static_assert(std::size(kClasses) == 5 + gpu::kMaxPlantCategories, "one entry per vegetation category");

} // namespace

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

} // namespace sward
