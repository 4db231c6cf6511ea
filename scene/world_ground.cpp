#include "scene/world_ground.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "io/raster_file.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>

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

// The lattice's heights over a window, row-major from the south-west corner. A DEM's nodata and non-finite samples
// are NaN and heights beyond 1e6 m kept as computed: the caller refuses them inside a tile and skips a skirt side
// holding one.
struct Samples {
    uint32_t columns = 0, rows = 0;
    int64_t firstColumn = 0, firstRow = 0; // a DEM's pixel of sample (0, rows - 1), the window's north-west one
    std::vector<float> heights;
    float at(uint32_t i, uint32_t j) const { return heights[size_t(j) * columns + i]; }
};

bool usable(float height) {
    return std::abs(height) <= 1e6f;
}

Samples proceduralSamples(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi) {
    ProceduralTerrainParams window = scene.terrain.procedural;
    window.origin = lo;
    window.size = float(std::max(hi.x - lo.x, hi.y - lo.y));
    Heightfield square = makeProceduralTerrain(window);
    const double s = window.spacing;
    Samples out{.columns = uint32_t(std::lround((hi.x - lo.x) / s)) + 1,
                .rows = uint32_t(std::lround((hi.y - lo.y) / s)) + 1};
    require(out.columns <= square.columns() && out.rows <= square.rows(),
            "worldHeights: the window is not on the lattice");
    // The terrain is made square; a window of another shape is its south-west part (a height depends on its lattice
    // point alone).
    out.heights.resize(size_t(out.columns) * out.rows);
    for (uint32_t j = 0; j < out.rows; ++j)
        for (uint32_t i = 0; i < out.columns; ++i) out.heights[size_t(j) * out.columns + i] = square.sample(i, j);
    return out;
}

// The DEM's lattice indices of a window's corner, refused off the lattice or beyond the DEM.
glm::i64vec2 demIndex(const Scene& scene, const WorldLattice& lattice, glm::dvec2 p, glm::dvec2 lo, glm::dvec2 hi) {
    const auto i = latticeIndex(p.x, lattice.origin.x, lattice.spacing);
    const auto j = latticeIndex(p.y, lattice.origin.y, lattice.spacing);
    require(i && j, demName(scene) + ": the window " + xyText(lo) + " .. " + xyText(hi) +
                        " does not lie on the DEM's samples (every " + formatNumber(lattice.spacing) + " m from " +
                        xyText(lattice.origin) + ")");
    require(*i >= 0 && *j >= 0 && *i < int64_t(lattice.samples.x) && *j < int64_t(lattice.samples.y),
            demName(scene) + ": the window " + xyText(lo) + " .. " + xyText(hi) + " reaches beyond the DEM's " +
                std::to_string(lattice.samples.x) + "x" + std::to_string(lattice.samples.y) + " samples, " +
                xyText(lattice.origin) + " .. " + xyText(lattice.last()));
    return {*i, *j};
}

// The DEM's blocks of kDemBlock x kDemBlock pixels most recently read, shared by every reader in the process: the
// cameras', actors' and objects' small windows of each tick and frame (sward-render computes every frame's record
// up front: examples/gis-world's 5,050 frames opened its DEM 30,401 times, 21 s) and the tiles' windows then cost
// one GDAL read per block. A block is the raster's pixels as read, so a height is bitwise the same whether it came
// from the cache or the file (the file is still opened once, by fitWorldToDem at every scene load, so the door logs
// it and its companions for each dataset's fingerprint). At most kDemCachedBlocks blocks (16 MiB), the least recently used dropped first.
constexpr uint32_t kDemBlock = 128, kDemCachedBlocks = 128;

class DemBlockCache {
public:
    // The raster's pixels [column, column + width) x [row, row + height), row-major from the top row, and its nodata.
    RasterBand window(const Scene& scene, uint32_t column, uint32_t row, uint32_t width, uint32_t height) {
        const HeightmapParams& h = scene.terrain.heightmap;
        RasterBand out{.width = width, .height = height, .values = std::vector<double>(size_t(width) * height)};
        for (uint32_t by = row / kDemBlock; by <= (row + height - 1) / kDemBlock; ++by)
            for (uint32_t bx = column / kDemBlock; bx <= (column + width - 1) / kDemBlock; ++bx) {
                const std::shared_ptr<const RasterBand> block = get(scene, bx, by);
                out.nodata = block->nodata;
                const uint32_t x0 = std::max(column, bx * kDemBlock), y0 = std::max(row, by * kDemBlock);
                const uint32_t x1 = std::min(column + width, bx * kDemBlock + block->width);
                const uint32_t y1 = std::min(row + height, by * kDemBlock + block->height);
                for (uint32_t y = y0; y < y1; ++y)
                    for (uint32_t x = x0; x < x1; ++x)
                        out.values[size_t(y - row) * width + (x - column)] =
                            block->at(x - bx * kDemBlock, y - by * kDemBlock);
            }
        out.source = h.path;
        return out;
    }

private:
    // The file's path, size and modification time (a DEM rewritten in place is read again), and the block.
    using Key = std::tuple<std::string, uintmax_t, int64_t, uint32_t, uint32_t>;
    std::shared_ptr<const RasterBand> get(const Scene& scene, uint32_t bx, uint32_t by) {
        const HeightmapParams& h = scene.terrain.heightmap;
        std::error_code sizeError, timeError;
        const uintmax_t size = std::filesystem::file_size(h.path, sizeError);
        const auto time = std::filesystem::last_write_time(h.path, timeError);
        const Key key{h.path, sizeError ? 0 : size, timeError ? 0 : int64_t(time.time_since_epoch().count()), bx, by};
        {
            std::lock_guard lock(mutex_);
            if (auto it = blocks_.find(key); it != blocks_.end()) {
                it->second.used = ++clock_;
                return it->second.band;
            }
        }
        const uint32_t x = bx * kDemBlock, y = by * kDemBlock;
        auto band = std::make_shared<const RasterBand>(readRasterWindow(h.path,
                                                                        {.column = x,
                                                                         .row = y,
                                                                         .width = std::min(kDemBlock, h.columns - x),
                                                                         .height = std::min(kDemBlock, h.rows - y)},
                                                                        {.folders = scene.assets.folders()}));
        std::lock_guard lock(mutex_);
        if (blocks_.size() >= kDemCachedBlocks) {
            auto oldest = std::min_element(blocks_.begin(), blocks_.end(),
                                           [](const auto& a, const auto& b) { return a.second.used < b.second.used; });
            blocks_.erase(oldest);
        }
        blocks_[key] = Entry{band, ++clock_};
        return band;
    }

    struct Entry {
        std::shared_ptr<const RasterBand> band;
        uint64_t used = 0;
    };
    std::mutex mutex_;
    std::map<Key, Entry> blocks_;
    uint64_t clock_ = 0;
};

DemBlockCache& demBlocks() {
    static DemBlockCache cache;
    return cache;
}

Samples demSamples(const Scene& scene, glm::i64vec2 first, glm::i64vec2 last) {
    const HeightmapParams& h = scene.terrain.heightmap;
    Samples out{.columns = uint32_t(last.x - first.x + 1),
                .rows = uint32_t(last.y - first.y + 1),
                .firstColumn = first.x,
                .firstRow = int64_t(h.rows) - 1 - last.y}; // raster rows run north to south
    RasterBand raster;
    try {
        raster = demBlocks().window(scene, uint32_t(first.x), uint32_t(out.firstRow), out.columns, out.rows);
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.heightmap': " + e.what());
    }
    // Heights as loadHeightfield computes them, so a one-tile scene of the same DEM stands on the same surface.
    const float scale = float(h.heightScale), offset = float(h.heightOffset);
    out.heights.resize(size_t(out.columns) * out.rows);
    for (uint32_t row = 0; row < out.rows; ++row)
        for (uint32_t i = 0; i < out.columns; ++i) {
            const double value = raster.at(i, row);
            const bool hole = raster.isNodata(value) || !std::isfinite(value);
            out.heights[size_t(out.rows - 1 - row) * out.columns + i] =
                hole ? std::numeric_limits<float>::quiet_NaN() : float(value) * scale + offset;
        }
    return out;
}

// Sample (i, j) of the window (its south-west at `lo`) is a hole or beyond 1e6 m: the one error, naming the file,
// the sample's world position and its pixel. A world's DEM is not filled.
[[noreturn]] void refuseSample(const Scene& scene, const Samples& samples, glm::dvec2 lo, double spacing, uint32_t i,
                               uint32_t j) {
    const glm::dvec2 p = lo + spacing * glm::dvec2(double(i), double(j));
    const bool hole = std::isnan(samples.at(i, j));
    // The tile holding it (on a border: the one east / north of it), whichever read met it first.
    const glm::dvec2 tile =
        glm::floor((p - glm::dvec2(scene.vegetation.worldOrigin)) / double(scene.vegetation.tileSize));
    const glm::dvec2 tiles(scene.world.tilesX, scene.world.tilesY);
    const glm::dvec2 inside = glm::min(tile, tiles - 1.0);
    const std::string where = tile.x >= 0.0 && tile.y >= 0.0 && tile.x <= tiles.x && tile.y <= tiles.y
                                  ? " in tile (" + formatNumber(inside.x) + ", " + formatNumber(inside.y) + ")"
                                  : " near the world";
    throw Error(demName(scene) + " has " + (hole ? "a nodata or non-finite sample" : "a height beyond 1e6 m") +
                " at world " + xyText(p) + " (pixel " + std::to_string(samples.firstColumn + i) + ", " +
                std::to_string(samples.firstRow + (samples.rows - 1 - j)) + ")" + where +
                ": a world's DEM is not filled; fill it first (e.g. gdal_fillnodata.py) or move "
                "'vegetation.world_origin' / 'world.tiles'");
}

// The heightfield of samples [i0, i0 + columns) x [j0, j0 + rows) of `samples`, its south-west sample at `lo`.
Heightfield cut(const Scene& scene, const Samples& samples, glm::dvec2 lo, double spacing, uint32_t i0, uint32_t j0,
                uint32_t columns, uint32_t rows) {
    std::vector<float> heights(size_t(columns) * rows);
    for (uint32_t j = 0; j < rows; ++j)
        for (uint32_t i = 0; i < columns; ++i) {
            const float h = samples.at(i0 + i, j0 + j);
            if (!usable(h)) refuseSample(scene, samples, lo - spacing * glm::dvec2(i0, j0), spacing, i0 + i, j0 + j);
            heights[size_t(j) * columns + i] = h;
        }
    return Heightfield(columns, rows, float(spacing), glm::vec2(lo), std::move(heights));
}

// One side of a skirt: `count` samples from (i, j) in steps of (di, dj); empty when any is missing or unusable.
std::vector<float> skirtSide(const Samples& samples, bool present, int64_t i, int64_t j, int64_t di, int64_t dj,
                             uint32_t count) {
    std::vector<float> side;
    if (!present) return side;
    for (uint32_t k = 0; k < count; ++k) {
        const float h = samples.at(uint32_t(i + di * k), uint32_t(j + dj * k));
        if (!usable(h)) return {};
        side.push_back(h);
    }
    return side;
}

// The window's samples and, with `skirt`, one more on each side where the lattice has it: a heightfield over
// [lo, hi] whose edge normals take the samples beyond.
Heightfield latticeHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi, bool skirt) {
    const WorldLattice lattice = worldLattice(scene);
    const double s = lattice.spacing;
    const int64_t margin = skirt ? 1 : 0;
    Samples samples;
    glm::i64vec2 below{margin, margin},
        above{margin, margin}; // samples read beyond the window's south-west and north-east
    if (!lattice.bounded()) {
        samples = proceduralSamples(scene, lo - double(margin) * s, hi + double(margin) * s);
    } else {
        const glm::i64vec2 first = demIndex(scene, lattice, lo, lo, hi), last = demIndex(scene, lattice, hi, lo, hi);
        require(last.x > first.x && last.y > first.y,
                demName(scene) + ": the window " + xyText(lo) + " .. " + xyText(hi) + " is empty");
        below = glm::min(first, glm::i64vec2(margin));
        above = glm::min(glm::i64vec2(lattice.samples) - int64_t(1) - last, glm::i64vec2(margin));
        samples = demSamples(scene, first - below, last + above);
    }
    const uint32_t columns = samples.columns - uint32_t(below.x + above.x);
    const uint32_t rows = samples.rows - uint32_t(below.y + above.y);
    Heightfield field = cut(scene, samples, lo, s, uint32_t(below.x), uint32_t(below.y), columns, rows);
    if (skirt)
        field.setSkirt(
            HeightfieldSkirt{.south = skirtSide(samples, below.y > 0, below.x, 0, 1, 0, columns),
                             .north = skirtSide(samples, above.y > 0, below.x, samples.rows - 1, 1, 0, columns),
                             .west = skirtSide(samples, below.x > 0, 0, below.y, 0, 1, rows),
                             .east = skirtSide(samples, above.x > 0, samples.columns - 1, below.y, 0, 1, rows)});
    return field;
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
    return latticeHeights(scene, lo, hi, false);
}

Heightfield worldTileHeights(const Scene& scene, glm::dvec2 lo, glm::dvec2 hi) {
    return latticeHeights(scene, lo, hi, true);
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
            const Heightfield part = worldHeights(scene, a, b);
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
