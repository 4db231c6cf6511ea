#include "scene/land_cover_params.h"

#include "common/error.h"
#include "common/parse_number.h"
#include "scene/scene.h"
#include "scene/world_ground.h"

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

// The world tile whose south-west corner is `origin`: generateWorldTile's tiles lie on the world's grid, so the
// nearest whole tile is exact.
glm::uvec2 worldTileAt(const Scene& scene, glm::dvec2 origin, const char* what) {
    const VegetationParams& v = scene.vegetation;
    const glm::dvec2 tile = glm::round((origin - glm::dvec2(v.worldOrigin)) / double(v.tileSize));
    require(tile.x >= 0.0 && tile.y >= 0.0 && tile.x < scene.world.tilesX && tile.y < scene.world.tilesY,
            scene.source + ": " + what + ": the tile is outside the world");
    return glm::uvec2(tile);
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

LandCoverWorld landCoverWorld(const Scene& scene) {
    LandCoverWorld world{
        .tilesX = scene.world.tilesX, .tilesY = scene.world.tilesY, .tileSize = double(scene.vegetation.tileSize)};
    // A DEM georeferenced in metres puts the world somewhere on Earth: a georeferenced land cover lies where its own
    // georeferencing puts it, so the two line up as in any GIS (the DEM's spacing from its header only: an explicit
    // metres_per_pixel overrides the georeferencing, and the land cover then starts at the world's corner).
    const HeightmapParams& h = scene.terrain.heightmap;
    if (!demWorld(scene) || h.metresPerPixel > 0.0) return world;
    const RasterInfo dem = readRasterInfo(h.path, {.folders = scene.assets.folders()});
    if (!dem.geoTransform || !(dem.geoTransform->metresPerUnit > 0.0)) return world;
    const RasterGeoTransform& g = *dem.geoTransform;
    const glm::dvec2 southWestSample(g.originX + 0.5 * g.pixelWidth, g.originY - (dem.height - 0.5) * g.pixelHeight);
    world.projectedOrigin = southWestSample + (glm::dvec2(scene.vegetation.worldOrigin) - h.origin) / g.metresPerUnit;
    world.metresPerUnit = g.metresPerUnit;
    world.tolerance = 0.5 * h.spacing;
    return world;
}

LandCoverGrid worldLandCoverGrid(const Scene& scene) {
    const std::string what = scene.source + ": 'land_cover'";
    RasterInfo info;
    try {
        info = readRasterInfo(scene.landCover.file, {.band = scene.landCover.band, .folders = scene.assets.folders()});
    } catch (const Error& e) {
        throw Error(what + ": " + e.what()); // which key named the file
    }
    return landCoverGrid(info.width, info.height, info.geoTransform, info.source, landCoverWorld(scene), what);
}

GrassMap worldLandCoverGrassMap(const Scene& scene, glm::dvec2 origin, uint32_t threads) {
    return loadLandCoverTileGrassMap(scene.landCover, landCoverWorld(scene), worldTileAt(scene, origin, "'land_cover'"),
                                     scene.source + ": 'land_cover'", threads, scene.assets.folders());
}

GrassMap worldLandCoverPointMap(const Scene& scene, glm::dvec2 origin, double side, uint32_t resolution) {
    return loadLandCoverPointGrassMap(scene.landCover, landCoverWorld(scene),
                                      origin - glm::dvec2(scene.vegetation.worldOrigin), side, resolution,
                                      scene.source + ": 'land_cover'", scene.assets.folders());
}

namespace {

GrassMap loadWorldGrassMap(const Scene& scene) {
    try {
        return loadGrassMap(scene.grassMapPath);
    } catch (const Error& e) {
        throw Error(scene.source + ": 'grass_map': " + e.what()); // which key named the file
    }
}

LandCoverGrid grassMapGrid(const Scene& scene, const GrassMap& map) {
    return landCoverGrid(map.width(), map.height(), std::nullopt, map.source(), landCoverWorld(scene),
                         scene.source + ": 'grass_map'");
}

} // namespace

GrassMap worldGrassMapBound(const Scene& scene, glm::uvec2& pixelsPerTile) {
    const GrassMap map = loadWorldGrassMap(scene);
    pixelsPerTile = grassMapGrid(scene, map).pixelsPerTile;
    std::vector<float> most(map.channels(), 0.0f);
    for (size_t i = 0; i < map.values().size(); ++i)
        most[i % map.channels()] = std::max(most[i % map.channels()], map.values()[i]);
    return GrassMap(1, 1, map.channels(), std::move(most), "the largest intensities of " + map.source());
}

GrassMap worldGrassMapWindow(const Scene& scene, glm::dvec2 origin) {
    const GrassMap map = loadWorldGrassMap(scene);
    const LandCoverGrid grid = grassMapGrid(scene, map);
    const glm::uvec2 tile = worldTileAt(scene, origin, "worldGrassMapWindow"), ppt = grid.pixelsPerTile;
    const uint32_t channels = map.channels(), top = map.height() - (tile.y + 1) * ppt.y;
    std::vector<float> values;
    values.reserve(size_t(ppt.x) * ppt.y * channels);
    for (uint32_t y = top; y < top + ppt.y; ++y) {
        const auto row =
            map.values().begin() + ptrdiff_t((size_t(y) * map.width() + size_t(tile.x) * ppt.x) * channels);
        values.insert(values.end(), row, row + ptrdiff_t(ppt.x * channels));
    }
    return GrassMap(ppt.x, ppt.y, channels, std::move(values), map.source());
}

} // namespace sward
