#include "scene/world_ground.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "io/raster_file.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

std::string demName(const Scene& scene) {
    return scene.source + ": 'terrain.heightmap' ('" + scene.terrain.heightmap.path + "')";
}

std::string xyText(glm::dvec2 p) {
    return "(" + formatNumber(p.x) + ", " + formatNumber(p.y) + ")";
}

// The lattice index of coordinate x (origin o, spacing s); nothing when x lies off the lattice.
std::optional<int64_t> latticeIndex(double x, double o, double s) {
    const double k = std::floor((x - o) / s + 0.5);
    if (!(std::abs(k * s - (x - o)) <= 1e-6 * std::max({1.0, std::abs(x), std::abs(o)}))) return std::nullopt;
    return int64_t(k);
}

Heightfield proceduralHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi) {
    ProceduralTerrainParams window = scene.terrain.procedural;
    window.origin = lo;
    window.size = float(std::max(hi.x - lo.x, hi.y - lo.y));
    Heightfield square = makeProceduralTerrain(window);
    const double s = window.spacing;
    const uint32_t columns = uint32_t(std::lround((hi.x - lo.x) / s)) + 1,
                   rows = uint32_t(std::lround((hi.y - lo.y) / s)) + 1;
    if (columns == square.columns() && rows == square.rows()) return square;
    require(columns <= square.columns() && rows <= square.rows(), "worldHeights: the window is not on the lattice");
    // The terrain is made square; a window of another shape is its south-west part (heights depend on the lattice
    // point alone).
    std::vector<float> heights(size_t(columns) * rows);
    for (uint32_t j = 0; j < rows; ++j)
        for (uint32_t i = 0; i < columns; ++i) heights[size_t(j) * columns + i] = square.sample(i, j);
    return Heightfield(columns, rows, square.spacing(), square.origin(), std::move(heights));
}

Heightfield demHeights(const Scene& scene, const WorldLattice& lattice, glm::dvec2 lo, glm::dvec2 hi) {
    const HeightmapParams& h = scene.terrain.heightmap;
    const double s = lattice.spacing;
    const auto i0 = latticeIndex(lo.x, lattice.origin.x, s), i1 = latticeIndex(hi.x, lattice.origin.x, s);
    const auto j0 = latticeIndex(lo.y, lattice.origin.y, s), j1 = latticeIndex(hi.y, lattice.origin.y, s);
    require(i0 && i1 && j0 && j1, demName(scene) + ": the window " + xyText(lo) + " .. " + xyText(hi) +
                                      " does not lie on the DEM's samples (every " + formatNumber(s) + " m from " +
                                      xyText(lattice.origin) + ")");
    require(*i0 >= 0 && *j0 >= 0 && *i1 > *i0 && *j1 > *j0 && *i1 < int64_t(h.columns) && *j1 < int64_t(h.rows),
            demName(scene) + ": the window " + xyText(lo) + " .. " + xyText(hi) + " reaches beyond the DEM's " +
                std::to_string(h.columns) + "x" + std::to_string(h.rows) + " samples, " + xyText(lattice.origin) +
                " .. " + xyText(lattice.last()));
    const uint32_t columns = uint32_t(*i1 - *i0 + 1), rows = uint32_t(*j1 - *j0 + 1);
    const uint32_t topRow = h.rows - 1 - uint32_t(*j1); // raster rows run north to south
    RasterBand raster;
    try {
        raster = readRasterWindow(h.path, {.column = uint32_t(*i0), .row = topRow, .width = columns, .height = rows},
                                  {.folders = scene.assets.folders()});
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.heightmap': " + e.what());
    }
    // Heights as loadHeightfield computes them, so a one-tile scene of the same DEM stands on the same surface.
    const float scale = float(h.heightScale), offset = float(h.heightOffset);
    std::vector<float> heights(size_t(columns) * rows);
    for (uint32_t row = 0; row < rows; ++row)
        for (uint32_t i = 0; i < columns; ++i) {
            const double value = raster.at(i, row);
            const float height = float(value) * scale + offset;
            const uint32_t j = rows - 1 - row;
            const bool hole = raster.isNodata(value) || !std::isfinite(value);
            if (hole || !(std::abs(height) <= 1e6f)) {
                const glm::dvec2 p = lattice.origin + s * glm::dvec2(double(*i0 + i), double(*j0 + j));
                throw Error(demName(scene) + " has " +
                            (hole ? "a nodata or non-finite sample" : "a height beyond 1e6 m") + " at world " +
                            xyText(p) + " (pixel " + std::to_string(*i0 + i) + ", " + std::to_string(topRow + row) +
                            ") inside the world: a world's DEM is not filled; fill it first (e.g. "
                            "gdal_fillnodata.py) or move 'vegetation.world_origin' / 'world.tiles'");
            }
            heights[size_t(j) * columns + i] = height;
        }
    const glm::dvec2 origin = lattice.origin + s * glm::dvec2(double(*i0), double(*j0));
    return Heightfield(columns, rows, float(s), glm::vec2(origin), std::move(heights));
}

} // namespace

bool demWorld(const Scene& scene) {
    return scene.world.enabled && scene.terrain.source == TerrainParams::Source::Heightmap;
}

WorldLattice worldLattice(const Scene& scene) {
    if (!demWorld(scene)) return WorldLattice{.spacing = double(scene.terrain.procedural.spacing)};
    const HeightmapParams& h = scene.terrain.heightmap;
    require(h.spacing > 0.0 && h.columns >= 2 && h.rows >= 2, "worldLattice: the world's DEM has not been read");
    return WorldLattice{.origin = h.origin, .spacing = h.spacing, .samples = glm::uvec2(h.columns, h.rows)};
}

Heightfield worldHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi) {
    if (!demWorld(scene)) return proceduralHeights(scene, lo, hi);
    return demHeights(scene, worldLattice(scene), lo, hi);
}

std::pair<float, float> worldHeightRange(const Scene& scene) {
    if (!demWorld(scene)) {
        const float half = 0.5f * std::abs(scene.terrain.procedural.amplitude);
        return {-half, half};
    }
    // The DEM under the world's tiles, in windows of at most 2048 x 2048 samples (32 MiB of doubles).
    const WorldLattice lattice = worldLattice(scene);
    const glm::dvec2 lo(scene.vegetation.worldOrigin);
    const glm::dvec2 hi = lo + double(scene.vegetation.tileSize) * glm::dvec2(scene.world.tilesX, scene.world.tilesY);
    const glm::dvec2 cells = glm::round((hi - lo) / lattice.spacing);
    constexpr double kChunk = 2047.0;
    float least = INFINITY, most = -INFINITY;
    for (double y = 0.0; y < cells.y; y += kChunk)
        for (double x = 0.0; x < cells.x; x += kChunk) {
            const glm::dvec2 a = lo + lattice.spacing * glm::dvec2(x, y);
            const glm::dvec2 b = lo + lattice.spacing * glm::min(glm::dvec2(x, y) + kChunk, cells);
            const Heightfield part = demHeights(scene, lattice, a, b);
            least = std::min(least, part.minHeight());
            most = std::max(most, part.maxHeight());
        }
    return {least, most};
}

void fitWorldToDem(Scene& scene, bool tilesGiven) {
    HeightmapParams& h = scene.terrain.heightmap;
    const std::string name = scene.source + ": 'terrain.heightmap'";
    if (!heightfieldNeedsGdal(h.path))
        throw Error(name + " ('" + h.path +
                    "'): a world reads its DEM window by window through GDAL; a PNG / EXR heightmap is read whole. "
                    "Convert it to a GeoTIFF (gdal_translate) and give 'metres_per_pixel'");
    RasterInfo info;
    float spacing = 0.0f;
    try {
        info = readRasterInfo(h.path, {.folders = scene.assets.folders()});
        spacing = rasterSpacing(info.geoTransform, h.path, float(h.metresPerPixel));
    } catch (const Error& e) {
        throw Error(name + ": " + e.what());
    }
    if (info.width < 2 || info.height < 2)
        throw Error(name + " ('" + h.path + "') has " + std::to_string(info.width) + "x" + std::to_string(info.height) +
                    " samples; a world's DEM needs at least 2x2");
    h.columns = info.width;
    h.rows = info.height;
    h.spacing = double(spacing); // the float the tiles' heightfields carry, so the lattice is theirs exactly
    VegetationParams& v = scene.vegetation;
    if (!scene.vegetationOriginSet) v.worldOrigin = glm::vec2(h.origin);
    if (tilesGiven) return;
    const WorldLattice lattice = worldLattice(scene);
    const glm::dvec2 span = (lattice.last() - glm::dvec2(v.worldOrigin)) / double(v.tileSize);
    const glm::dvec2 tiles = glm::floor(span + 1e-9);
    if (!(tiles.x >= 1.0 && tiles.y >= 1.0))
        throw Error(name + " ('" + h.path + "'): the DEM from 'vegetation.world_origin' " +
                    xyText(glm::dvec2(v.worldOrigin)) + " to its north-east sample " + xyText(lattice.last()) +
                    " holds no whole tile of 'vegetation.tile_size' (" + formatNumber(v.tileSize) + " m)");
    if (tiles.x > kMaxWorldTilesPerSide || tiles.y > kMaxWorldTilesPerSide)
        throw Error(name + " ('" + h.path + "') spans " + formatNumber(tiles.x) + " x " + formatNumber(tiles.y) +
                    " tiles of 'vegetation.tile_size' (" + formatNumber(v.tileSize) + " m), more than " +
                    std::to_string(kMaxWorldTilesPerSide) + " a side: give 'world.tiles' or a larger tile");
    scene.world.tilesX = uint32_t(tiles.x);
    scene.world.tilesY = uint32_t(tiles.y);
}

void checkDemWorld(const Scene& scene) {
    const WorldLattice lattice = worldLattice(scene);
    const VegetationParams& v = scene.vegetation;
    const std::string source = scene.source + ": ";
    const double s = lattice.spacing;
    const auto cells = latticeIndex(double(v.tileSize), 0.0, s);
    if (!cells || *cells < 1)
        throw Error(source + "in a world on a DEM 'vegetation.tile_size' (" + formatNumber(v.tileSize) +
                    " m) must be a whole number of the DEM's samples (" + formatNumber(s) +
                    " m apart), so the tiles' heightfields meet on its samples");
    if (*cells > int64_t(kMaxHeightfieldCells))
        throw Error(source + "'vegetation.tile_size' (" + formatNumber(v.tileSize) + " m) holds " +
                    std::to_string(*cells) + " DEM samples a side, more than a tile's " +
                    std::to_string(kMaxHeightfieldCells) + " cells: lower it");
    const glm::dvec2 origin(v.worldOrigin);
    if (!latticeIndex(origin.x, lattice.origin.x, s) || !latticeIndex(origin.y, lattice.origin.y, s))
        throw Error(source + "in a world on a DEM 'vegetation.world_origin' " + xyText(origin) +
                    " must lie on the DEM's samples (every " + formatNumber(s) + " m from 'terrain.heightmap.origin' " +
                    xyText(lattice.origin) + ")");
    const glm::dvec2 far = origin + double(v.tileSize) * glm::dvec2(scene.world.tilesX, scene.world.tilesY);
    const glm::dvec2 last = lattice.last();
    const double slack = 1e-6 * std::max({1.0, std::abs(last.x), std::abs(last.y)});
    if (origin.x < lattice.origin.x - slack || origin.y < lattice.origin.y - slack || far.x > last.x + slack ||
        far.y > last.y + slack)
        throw Error(source + "'world.tiles' (" + std::to_string(scene.world.tilesX) + " x " +
                    std::to_string(scene.world.tilesY) + ") of 'vegetation.tile_size' (" + formatNumber(v.tileSize) +
                    " m) from 'vegetation.world_origin' " + xyText(origin) + " reach " + xyText(far) +
                    ", beyond the DEM 'terrain.heightmap' ('" + scene.terrain.heightmap.path + "'), which spans " +
                    xyText(lattice.origin) + " .. " + xyText(last));
}

} // namespace sward
