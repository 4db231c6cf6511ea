#include "vegetation/vegetation_params.h"

#include "common/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <set>

namespace sward {

VegetationCategory defaultVegetationCategory(uint32_t index) {
    switch (index) {
    case 0:
        return {.name = "ferns", .density = 1.5f, .height = 0.6f, .heightVariation = 0.3f, .variants = 4};
    case 1:
        return {.name = "grass", .density = 16.0f, .height = 0.35f, .heightVariation = 0.35f, .variants = 8};
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

std::string show(double v) {
    nlohmann::json j = v;
    return std::isfinite(v) ? j.dump() : (std::isnan(v) ? "NaN" : "infinity");
}

void requireRange(const std::string& source, const std::string& key, double value, double lo, double hi) {
    require(std::isfinite(value) && value >= lo && value <= hi, source + ": vegetation '" + key +
                                                                    "' must be a number in [" + show(lo) + ", " +
                                                                    show(hi) + "] (got " + show(value) + ")");
}

} // namespace

uint32_t VegetationParams::fieldsPerTile() const {
    return wholeRatio(tileSize, fieldSize);
}
uint32_t VegetationParams::clustersPerField() const {
    return wholeRatio(fieldSize, clusterSize);
}

void validateVegetationParams(const VegetationParams& p, const std::string& source) {
    requireRange(source, "field_size", p.fieldSize, 1.0, 256.0);
    requireRange(source, "cluster_size", p.clusterSize, 0.5, 256.0);
    requireRange(source, "tile_size", p.tileSize, 1.0, 65536.0);
    require(p.fieldsPerTile() != 0 && p.fieldsPerTile() <= 1024, source + ": vegetation 'tile_size' (" +
                                                                     show(p.tileSize) +
                                                                     ") must be a whole multiple (at most 1024) of "
                                                                     "'field_size' (" +
                                                                     show(p.fieldSize) + ")");
    require(p.clustersPerField() != 0 && p.clustersPerField() <= 64, source + ": vegetation 'field_size' (" +
                                                                         show(p.fieldSize) +
                                                                         ") must be a whole multiple (at most 64) "
                                                                         "of 'cluster_size' (" +
                                                                         show(p.clusterSize) + ")");
    requireRange(source, "world_origin[0]", p.worldOrigin.x, -1e7, 1e7);
    requireRange(source, "world_origin[1]", p.worldOrigin.y, -1e7, 1e7);
    requireRange(source, "density_multiplier", p.densityMultiplier, 0.0, 100.0);
    requireRange(source, "up_normal_blend", p.upNormalBlend, 0.0, 1.0);
    require(p.memoryBudgetBytes > 0, source + ": vegetation 'memory_budget_mib' must be positive");
    require(p.categoryCount >= 1 && p.categoryCount <= gpu::kMaxPlantCategories,
            source + ": vegetation 'categories' must list 1 to 4 categories");
    for (uint32_t i = 0; i < p.categoryCount; ++i) {
        const VegetationCategory& c = p.categories[i];
        const std::string key = "categories[" + std::to_string(i) + "].";
        requireRange(source, key + "density", c.density, 0.0, 1000.0);
        requireRange(source, key + "height", c.height, 0.01, 20.0);
        requireRange(source, key + "height_variation", c.heightVariation, 0.0, 0.95);
        require(c.variants >= 1 && c.variants <= gpu::kMaxPlantVariants,
                source + ": vegetation '" + key + "variants' must be 1..64 (got " + std::to_string(c.variants) + ")");
    }
    for (uint32_t ch = 0; ch < 4; ++ch) {
        int32_t cat = p.channelCategory[ch];
        require(cat == kUnusedChannel || (cat >= 0 && uint32_t(cat) < p.categoryCount),
                source + ": vegetation 'channels." + "rgba"[ch] + "' refers to category " + std::to_string(cat) +
                    ", but only " + std::to_string(p.categoryCount) + " categories exist");
    }
}

namespace {

using Json = nlohmann::json;

void requireKeys(const Json& object, const std::set<std::string>& known, const std::string& source,
                 const std::string& where) {
    require(object.is_object(), source + ": vegetation '" + where + "' must be a JSON object");
    for (auto it = object.begin(); it != object.end(); ++it)
        require(known.count(it.key()) != 0,
                source + ": unknown vegetation key '" + where + (where.empty() ? "" : ".") + it.key() + "'");
}

double number(const Json& value, const std::string& source, const std::string& key) {
    require(value.is_number(), source + ": vegetation '" + key + "' must be a number (got " + value.dump() + ")");
    return value.get<double>();
}

uint64_t unsignedInteger(const Json& value, const std::string& source, const std::string& key) {
    require(value.is_number_unsigned() || (value.is_number_integer() && value.get<int64_t>() >= 0),
            source + ": vegetation '" + key + "' must be a non-negative integer (got " + value.dump() + ")");
    return value.get<uint64_t>();
}

// Numbers are read as double and range-checked by validateVegetationParams after narrowing; a double that does
// not fit a float becomes infinity and fails there with the original key name.
void readFloat(const Json& object, const char* key, float& out, const std::string& source,
               const std::string& prefix = "") {
    if (object.contains(key)) out = float(number(object.at(key), source, prefix + key));
}

} // namespace

VegetationParams parseVegetationParams(const Json& json, const std::string& source) {
    VegetationParams p;
    if (json.is_null()) return p;
    requireKeys(json,
                {"seed", "tile_size", "field_size", "cluster_size", "world_origin", "density_multiplier",
                 "up_normal_blend", "memory_budget_mib", "categories", "channels"},
                source, "");
    if (json.contains("seed")) p.seed = unsignedInteger(json.at("seed"), source, "seed");
    readFloat(json, "tile_size", p.tileSize, source);
    readFloat(json, "field_size", p.fieldSize, source);
    readFloat(json, "cluster_size", p.clusterSize, source);
    readFloat(json, "density_multiplier", p.densityMultiplier, source);
    readFloat(json, "up_normal_blend", p.upNormalBlend, source);
    if (json.contains("world_origin")) {
        const Json& o = json.at("world_origin");
        require(o.is_array() && o.size() == 2, source + ": vegetation 'world_origin' must be an array [x, y]");
        p.worldOrigin =
            glm::vec2(float(number(o[0], source, "world_origin[0]")), float(number(o[1], source, "world_origin[1]")));
    }
    if (json.contains("memory_budget_mib")) {
        double mib = number(json.at("memory_budget_mib"), source, "memory_budget_mib");
        requireRange(source, "memory_budget_mib", mib, 1.0, 1024.0 * 1024.0);
        p.memoryBudgetBytes = uint64_t(mib * 1048576.0);
    }
    if (json.contains("categories")) {
        const Json& list = json.at("categories");
        require(list.is_array() && !list.empty() && list.size() <= gpu::kMaxPlantCategories,
                source + ": vegetation 'categories' must be an array of 1 to 4 objects");
        p.categoryCount = uint32_t(list.size());
        for (uint32_t i = 0; i < p.categoryCount; ++i) {
            const std::string where = "categories[" + std::to_string(i) + "]";
            const Json& entry = list[i];
            requireKeys(entry, {"name", "density", "height", "height_variation", "variants"}, source, where);
            VegetationCategory& c = p.categories[i];
            if (entry.contains("name")) {
                require(entry.at("name").is_string(), source + ": vegetation '" + where + ".name' must be a string");
                c.name = entry.at("name").get<std::string>();
            }
            readFloat(entry, "density", c.density, source, where + ".");
            readFloat(entry, "height", c.height, source, where + ".");
            readFloat(entry, "height_variation", c.heightVariation, source, where + ".");
            if (entry.contains("variants")) {
                uint64_t v = unsignedInteger(entry.at("variants"), source, where + ".variants");
                c.variants = uint32_t(std::min<uint64_t>(v, 1u << 20)); // range-checked below
            }
        }
    }
    // The default mapping R, G, B -> 0, 1, 2 shrinks with a shorter category list instead of failing.
    for (int32_t& cat : p.channelCategory)
        if (cat != kUnusedChannel && uint32_t(cat) >= p.categoryCount) cat = kUnusedChannel;
    if (json.contains("channels")) {
        const Json& channels = json.at("channels");
        requireKeys(channels, {"r", "g", "b", "a"}, source, "channels");
        static const char* kNames[] = {"r", "g", "b", "a"};
        for (uint32_t ch = 0; ch < 4; ++ch) {
            if (!channels.contains(kNames[ch])) continue;
            const Json& v = channels.at(kNames[ch]);
            const std::string key = std::string("channels.") + kNames[ch];
            if (v.is_null()) {
                p.channelCategory[ch] = kUnusedChannel;
            } else if (v.is_string()) {
                int32_t found = kUnusedChannel;
                for (uint32_t i = 0; i < p.categoryCount; ++i)
                    if (p.categories[i].name == v.get<std::string>()) found = int32_t(i);
                require(found != kUnusedChannel,
                        source + ": vegetation '" + key + "' names unknown category " + v.dump());
                p.channelCategory[ch] = found;
            } else {
                uint64_t index = unsignedInteger(v, source, key);
                p.channelCategory[ch] = int32_t(std::min<uint64_t>(index, 1000)); // range-checked below
            }
        }
    }
    validateVegetationParams(p, source);
    return p;
}

glm::vec2 WindParams::direction() const {
    double a = directionDegrees * std::numbers::pi / 180.0;
    return glm::vec2(float(std::sin(a)), float(std::cos(a)));
}

} // namespace sward
