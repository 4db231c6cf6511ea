#include "vegetation/vegetation_params.h"

#include "common/error.h"
#include "common/json_reader.h"

#include <cmath>
#include <numbers>

namespace sward {

VegetationCategory defaultVegetationCategory(uint32_t index) {
    switch (index) {
    case 0:
        return {.name = "ferns", .density = 1.5f, .height = 0.6f, .heightVariation = 0.3f, .variants = 8};
    case 1:
        return {.name = "grass", .density = 16.0f, .height = 0.35f, .heightVariation = 0.35f, .variants = 12};
    case 2:
        return {.name = "flowers", .density = 1.0f, .height = 0.45f, .heightVariation = 0.4f, .variants = 8};
    default:
        return {.name = "extra", .density = 1.0f, .height = 0.5f, .heightVariation = 0.3f, .variants = 4};
    }
}

namespace {

// n if whole is n times part (to a relative 1e-5), else 0.
uint32_t wholeRatio(float whole, float part) {
    double ratio = double(whole) / double(part);
    double n = std::floor(ratio + 0.5);
    return n >= 1.0 && std::abs(ratio - n) <= 1e-5 * n ? uint32_t(n) : 0;
}

// The ranges of the documented keys: the parser refuses a value outside them naming its JSON path, and
// validateVegetationParams checks parameters built in code against the same ranges.
struct Range {
    double lo, hi;
};
constexpr Range kTileSize{1.0, 65536.0}, kFieldSize{1.0, 256.0}, kClusterSize{0.5, 256.0}, kWorldOrigin{-1e7, 1e7},
    kDensityMultiplier{0.0, 100.0}, kUpNormalBlend{0.0, 1.0}, kMemoryBudgetMib{1.0, 1024.0 * 1024.0},
    kDensity{0.0, 1000.0}, kHeight{0.01, 20.0}, kHeightVariation{0.0, 0.95}, kPatchSize{1.0, 200.0},
    kPatchiness{0.0, 1.0}, kHeightGradient{0.0, 0.9}, kClumping{0.0, 0.9}, kClumpSize{0.05, 5.0};

// Messages in the JSON reader's wording: "<source>: 'vegetation.<key>' must be ...".
std::string quoted(const std::string& key) {
    return "'vegetation." + key + "'";
}

void requireRange(const std::string& source, const std::string& key, double value, Range range) {
    require(std::isfinite(value) && value >= range.lo && value <= range.hi,
            source + ": " + quoted(key) + " must be between " + formatNumber(range.lo) + " and " +
                formatNumber(range.hi) + " (got " + formatNumber(value) + ")");
}

float readNumber(JsonReader& r, const char* key, float value, Range range) {
    return r.numberF(key, value, range.lo, range.hi);
}

} // namespace

uint32_t VegetationParams::fieldsPerTile() const {
    return wholeRatio(tileSize, fieldSize);
}
uint32_t VegetationParams::clustersPerField() const {
    return wholeRatio(fieldSize, clusterSize);
}

void validateVegetationParams(const VegetationParams& p, const std::string& source) {
    requireRange(source, "field_size", p.fieldSize, kFieldSize);
    requireRange(source, "cluster_size", p.clusterSize, kClusterSize);
    requireRange(source, "tile_size", p.tileSize, kTileSize);
    require(p.fieldsPerTile() != 0 && p.fieldsPerTile() <= kMaxFieldsPerTileSide,
            source + ": " + quoted("tile_size") + " (" + formatNumber(p.tileSize) +
                ") must be a whole multiple (at most " + std::to_string(kMaxFieldsPerTileSide) + ") of " +
                quoted("field_size") + " (" + formatNumber(p.fieldSize) + ")");
    require(p.clustersPerField() != 0 && p.clustersPerField() <= kMaxClustersPerFieldSide,
            source + ": " + quoted("field_size") + " (" + formatNumber(p.fieldSize) +
                ") must be a whole multiple (at most " + std::to_string(kMaxClustersPerFieldSide) + ") of " +
                quoted("cluster_size") + " (" + formatNumber(p.clusterSize) + ")");
    requireRange(source, "world_origin[0]", p.worldOrigin.x, kWorldOrigin);
    requireRange(source, "world_origin[1]", p.worldOrigin.y, kWorldOrigin);
    requireRange(source, "density_multiplier", p.densityMultiplier, kDensityMultiplier);
    requireRange(source, "up_normal_blend", p.upNormalBlend, kUpNormalBlend);
    require(p.memoryBudgetBytes > 0, source + ": " + quoted("memory_budget_mib") + " must be positive");
    require(p.categoryCount >= 1 && p.categoryCount <= gpu::kMaxPlantCategories,
            source + ": " + quoted("categories") + " must list 1 to 4 categories");
    for (uint32_t i = 0; i < p.categoryCount; ++i) {
        const VegetationCategory& c = p.categories[i];
        const std::string key = "categories[" + std::to_string(i) + "].";
        requireRange(source, key + "density", c.density, kDensity);
        requireRange(source, key + "height", c.height, kHeight);
        requireRange(source, key + "height_variation", c.heightVariation, kHeightVariation);
        require(c.variants >= 1 && c.variants <= gpu::kMaxPlantVariants, source + ": " + quoted(key + "variants") +
                                                                             " must be between 1 and 64 (got " +
                                                                             std::to_string(c.variants) + ")");
        require(c.groundMaterial >= kNoGroundMaterial && c.groundMaterial <= 4,
                source + ": " + quoted(key + "ground_material") + " must be a preset 0..4 or none (got " +
                    std::to_string(c.groundMaterial) + ")");
    }
    requireRange(source, "pattern.patch_size", p.pattern.patchSize, kPatchSize);
    requireRange(source, "pattern.patchiness", p.pattern.patchiness, kPatchiness);
    requireRange(source, "pattern.height_gradient", p.pattern.heightGradient, kHeightGradient);
    requireRange(source, "pattern.clumping", p.pattern.clumping, kClumping);
    requireRange(source, "pattern.clump_size", p.pattern.clumpSize, kClumpSize);
    for (uint32_t ch = 0; ch < 4; ++ch) {
        int32_t cat = p.channelCategory[ch];
        require(cat == kUnusedChannel || (cat >= 0 && uint32_t(cat) < p.categoryCount),
                source + ": " + quoted(std::string("channels.") + "rgba"[ch]) + " refers to category " +
                    std::to_string(cat) + ", but only " + std::to_string(p.categoryCount) + " categories exist");
    }
}

namespace {

void parseCategory(JsonReader r, VegetationCategory& c) {
    c.name = r.string("name", c.name);
    c.density = readNumber(r, "density", c.density, kDensity);
    c.height = readNumber(r, "height", c.height, kHeight);
    c.heightVariation = readNumber(r, "height_variation", c.heightVariation, kHeightVariation);
    c.variants = uint32_t(r.integer("variants", c.variants, 1, gpu::kMaxPlantVariants));
    // In the order of terrain.material's names (scene.cpp readTerrain).
    c.groundMaterial =
        r.choice("ground_material", c.groundMaterial, {"soil", "dry_soil", "mud", "gravel", "forest_floor"});
    r.finish();
}

void parsePattern(JsonReader r, MeadowPattern& m) {
    m.patchSize = readNumber(r, "patch_size", m.patchSize, kPatchSize);
    m.patchiness = readNumber(r, "patchiness", m.patchiness, kPatchiness);
    m.heightGradient = readNumber(r, "height_gradient", m.heightGradient, kHeightGradient);
    m.clumping = readNumber(r, "clumping", m.clumping, kClumping);
    m.clumpSize = readNumber(r, "clump_size", m.clumpSize, kClumpSize);
    r.finish();
}

// Grass-map channel -> category: an index, a category name, or null (unused). Whether the category exists is
// checked by validateVegetationParams.
void parseChannels(JsonReader r, VegetationParams& p) {
    static const char* kNames[] = {"r", "g", "b", "a"};
    for (uint32_t ch = 0; ch < 4; ++ch) {
        const nlohmann::json* v = r.raw(kNames[ch]);
        if (!v) continue;
        if (v->is_null()) {
            p.channelCategory[ch] = kUnusedChannel;
        } else if (v->is_string()) {
            int32_t found = kUnusedChannel;
            for (uint32_t i = 0; i < p.categoryCount; ++i)
                if (p.categories[i].name == v->get<std::string>()) found = int32_t(i);
            if (found == kUnusedChannel) r.fail(r.name(kNames[ch]) + " names unknown category " + v->dump());
            p.channelCategory[ch] = found;
        } else {
            p.channelCategory[ch] = int32_t(r.integer(kNames[ch], 0, 0, 1000));
        }
    }
    r.finish();
}

} // namespace

VegetationParams parseVegetationParams(const nlohmann::json& json, const std::string& source) {
    VegetationParams p;
    if (json.is_null()) return p;
    JsonReader r(json, source, "vegetation");
    p.seed = r.integer("seed", p.seed, 0, UINT64_MAX);
    p.tileSize = readNumber(r, "tile_size", p.tileSize, kTileSize);
    p.fieldSize = readNumber(r, "field_size", p.fieldSize, kFieldSize);
    p.clusterSize = readNumber(r, "cluster_size", p.clusterSize, kClusterSize);
    p.densityMultiplier = readNumber(r, "density_multiplier", p.densityMultiplier, kDensityMultiplier);
    p.upNormalBlend = readNumber(r, "up_normal_blend", p.upNormalBlend, kUpNormalBlend);
    p.worldOrigin = glm::vec2(r.vector<2>("world_origin", glm::dvec2(p.worldOrigin), kWorldOrigin.lo, kWorldOrigin.hi));
    if (r.has("memory_budget_mib"))
        p.memoryBudgetBytes =
            uint64_t(r.number("memory_budget_mib", 0.0, kMemoryBudgetMib.lo, kMemoryBudgetMib.hi) * 1048576.0);
    if (r.has("categories")) {
        const std::vector<JsonReader> categories = r.objects("categories");
        if (categories.empty() || categories.size() > gpu::kMaxPlantCategories)
            r.fail(r.name("categories") + " must be an array of 1 to 4 objects");
        p.categoryCount = uint32_t(categories.size());
        for (uint32_t i = 0; i < p.categoryCount; ++i) parseCategory(categories[i], p.categories[i]);
    }
    // The default mapping R, G, B -> 0, 1, 2 shrinks with a shorter category list instead of failing.
    for (int32_t& cat : p.channelCategory)
        if (cat != kUnusedChannel && uint32_t(cat) >= p.categoryCount) cat = kUnusedChannel;
    if (r.has("channels")) parseChannels(r.child("channels"), p);
    if (r.has("pattern")) parsePattern(r.child("pattern"), p.pattern);
    r.finish();
    validateVegetationParams(p, source);
    return p;
}

glm::vec2 WindParams::direction() const {
    double a = directionDegrees * std::numbers::pi / 180.0;
    return glm::vec2(float(std::sin(a)), float(std::cos(a)));
}

} // namespace sward
