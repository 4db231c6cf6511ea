#include "scene/land_cover_params.h"

#include "common/parse_number.h"

#include <map>
#include <string>

namespace sward {

namespace {

// "table": {"<code>": [r, g, b] or [r, g, b, a], ...}; an entry with a fourth intensity makes a four-channel map.
void readTable(const nlohmann::json& json, JsonReader t, LandCoverTable& table) {
    std::map<int64_t, std::string> keys; // code -> the key that named it ("10" and "010" are one code)
    for (const auto& [key, value] : json.items()) {
        const int64_t code = parseInteger(key, 0, kMaxLandCoverCode, t.source() + ": '" + t.path() + "' class code");
        if (const auto [it, added] = keys.emplace(code, key); !added)
            t.fail("'" + t.path() + "' names class code " + std::to_string(code) + " twice ('" + it->second +
                   "' and '" + key + "')");
        const double hi = kMaxLandCoverIntensity;
        if (!value.is_array() || (value.size() != 3 && value.size() != 4))
            t.fail(t.name(key) + " must be an array of 3 or 4 intensities (R, G, B[, A]) between 0 and " +
                   formatNumber(hi));
        if (value.size() == 4) {
            table.classes[code] = glm::vec4(t.vector<4>(key.c_str(), glm::dvec4(0.0), 0.0, hi));
            table.channels = 4;
        } else {
            table.classes[code] = glm::vec4(glm::vec3(t.vector<3>(key.c_str(), glm::dvec3(0.0), 0.0, hi)), 0.0f);
        }
    }
    t.finish();
}

} // namespace

LandCoverParams parseLandCoverParams(JsonReader& r) {
    LandCoverParams p;
    if (r.choice("preset", -1, {"esa_worldcover"}) == 0) p.table = esaWorldCoverTable();
    if (const nlohmann::json* table = r.raw("table"))
        readTable(*table, JsonReader(*table, r.source(), r.childPath("table")), p.table);
    if (p.table.classes.empty())
        r.fail("'" + r.path() + "' needs a 'preset' or a 'table' of class codes and their intensities");
    p.borderWidth = r.number("border", p.borderWidth, 0.0, kMaxLandCoverBorder);
    p.band = uint32_t(r.integer("band", p.band, 1, 65535));
    if (r.has("nodata")) {
        p.nodataCode = int64_t(r.integer("nodata", 0, 0, kMaxLandCoverCode));
        if (!p.table.find(*p.nodataCode))
            r.fail(r.name("nodata") + " is class code " + std::to_string(*p.nodataCode) + ", which the table lacks");
    }
    return p;
}

} // namespace sward
