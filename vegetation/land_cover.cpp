#include "vegetation/land_cover.h"

#include "common/error.h"
#include "common/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace sward {

const glm::vec4* LandCoverTable::find(int64_t code) const {
    const auto it = classes.find(code);
    return it == classes.end() ? nullptr : &it->second;
}

// Intensities are fractions of each category's full density (by default ferns 1.5, grass 16, shrubs and flowers
// 1 plant per m^2). The class definitions quoted are WorldCover's (product user manual, v100 / v200).
LandCoverTable esaWorldCoverTable() {
    const glm::vec4 bare(0.0f);
    LandCoverTable table;
    table.classes = {
        // Tree cover (trees of 10 % cover or more): a shaded forest floor of ferns and herbs; grass is thin under a
        // canopy, some understorey shrubs.
        {10, {0.8f, 0.15f, 0.2f, 0.0f}},
        // Shrubland (woody perennials under 5 m, 10 % cover or more): shrubs at full density, grass between them.
        {20, {0.2f, 0.4f, 1.0f, 0.0f}},
        // Grassland (herbaceous plants, 10 % cover or more): the full meadow, dense grass with flowers.
        {30, {0.05f, 1.0f, 0.3f, 0.0f}},
        // Cropland (sown and harvested within the year): crops are not modelled; stubble, margins and weeds stand in
        // as half-dense grass with a few flowers.
        {40, {0.0f, 0.5f, 0.1f, 0.0f}},
        // Built-up (buildings, roads, sealed surfaces): no vegetation; gardens lie below the 10 m pixels.
        {50, bare},
        // Bare / sparse vegetation (never more than 10 % cover): a tenth of the grass, rare flowers.
        {60, {0.0f, 0.1f, 0.05f, 0.0f}},
        // Snow and ice: nothing grows.
        {70, bare},
        // Permanent water bodies: nothing stands on open water.
        {80, bare},
        // Herbaceous wetland (regularly flooded herbs): reeds and sedges stand in as dense grass, marsh ferns.
        {90, {0.3f, 0.9f, 0.15f, 0.0f}},
        // Mangroves (woody stands on tidal mud): the shrub category stands in for young trees; almost no ground layer.
        {95, {0.05f, 0.05f, 0.6f, 0.0f}},
        // Moss and lichen: a low ground cover sward has no category for; the forest-floor category comes closest,
        // with sparse grass.
        {100, {0.4f, 0.2f, 0.05f, 0.0f}},
    };
    return table;
}

namespace {

// Each pixel's class as an index into `intensities`: the table's classes in code order, then (when nodata pixels
// count as no class) one entry of zeros.
struct ClassifiedRaster {
    std::vector<uint32_t> index;
    std::vector<glm::vec4> intensities;
};

// Pixel i of `raster`, whose top-left pixel is pixel `origin` of the file (a window's offset), in the file's terms.
std::string pixelText(const RasterBand& raster, size_t i, glm::uvec2 origin) {
    return "(" + std::to_string(i % raster.width + origin.x) + ", " + std::to_string(i / raster.width + origin.y) + ")";
}

std::string valueText(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", v);
    return text;
}

// "10, 20, 30" (at most 20 codes).
std::string tableCodes(const LandCoverTable& table) {
    std::string text;
    size_t listed = 0;
    for (const auto& entry : table.classes) {
        if (listed++ == 20) return text + ", ...";
        text += (text.empty() ? "" : ", ") + std::to_string(entry.first);
    }
    return text.empty() ? "none" : text;
}

ClassifiedRaster classify(const RasterBand& raster, const LandCoverParams& params, const std::string& what,
                          glm::uvec2 origin = glm::uvec2(0)) {
    ClassifiedRaster out;
    std::map<int64_t, uint32_t> indexOf;
    for (const auto& [code, intensities] : params.table.classes) {
        indexOf[code] = uint32_t(out.intensities.size());
        out.intensities.push_back(intensities);
    }
    uint32_t nodataIndex = uint32_t(out.intensities.size());
    if (params.nodataCode) {
        const auto it = indexOf.find(*params.nodataCode);
        require(it != indexOf.end(), what + ": the nodata class code " + std::to_string(*params.nodataCode) +
                                         " is not in the table (it has " + tableCodes(params.table) + ")");
        nodataIndex = it->second;
    } else {
        out.intensities.push_back(glm::vec4(0.0f));
    }
    out.index.resize(raster.values.size());
    // Land cover comes in runs of one class: the last code found is tried first. (It is never the nodata value.)
    std::optional<double> lastCode;
    uint32_t lastIndex = 0;
    for (size_t i = 0; i < raster.values.size(); ++i) {
        const double v = raster.values[i];
        if (v == lastCode) {
            out.index[i] = lastIndex;
            continue;
        }
        if (raster.isNodata(v)) {
            out.index[i] = nodataIndex;
            continue;
        }
        if (!(v >= 0.0 && v <= double(kMaxLandCoverCode) && v == std::floor(v)))
            throw Error(what + ": raster '" + raster.source + "' has the value " + valueText(v) + " at pixel " +
                        pixelText(raster, i, origin) + ", which is not a class code (a whole number 0.." +
                        std::to_string(kMaxLandCoverCode) + ")");
        const auto it = indexOf.find(int64_t(v));
        if (it == indexOf.end())
            throw Error(what + ": class code " + std::to_string(int64_t(v)) + " of raster '" + raster.source +
                        "' (first at pixel " + pixelText(raster, i, origin) + ") is not in the table (it has " +
                        tableCodes(params.table) + ")");
        lastCode = v;
        lastIndex = it->second;
        out.index[i] = lastIndex;
    }
    return out;
}

struct LineScratch {
    std::vector<double> prefix;   // prefix[i]: sum of the first i samples, added in order
    std::vector<uint32_t> runEnd; // last index of the run of equal samples holding i
};

// The exact box average along one line of n samples in[i * stride] (pixel i covers [i, i + 1)): the mean of the
// piecewise-constant line over [i + 0.5 - half, i + 0.5 + half] clipped to [0, n], into out[i * stride]. Where
// the box covers one run of equal samples the result is that sample exactly, not a quotient of sums.
void boxFilterLine(const double* in, double* out, size_t stride, uint32_t n, double half, LineScratch& s) {
    s.prefix.resize(size_t(n) + 1);
    s.runEnd.resize(n);
    s.prefix[0] = 0.0;
    for (uint32_t i = 0; i < n; ++i) s.prefix[i + 1] = s.prefix[i] + in[i * stride];
    s.runEnd[n - 1] = n - 1;
    for (uint32_t i = n - 1; i-- > 0;) s.runEnd[i] = in[i * stride] == in[(i + 1) * stride] ? s.runEnd[i + 1] : i;
    // The integral of the line over [0, t].
    auto integral = [&](double t) {
        const uint32_t k = std::min(uint32_t(t), n - 1);
        return s.prefix[k] + (t - double(k)) * in[k * stride];
    };
    for (uint32_t i = 0; i < n; ++i) {
        const double centre = double(i) + 0.5;
        const double a = std::max(0.0, centre - half), b = std::min(double(n), centre + half);
        const uint32_t first = std::min(uint32_t(a), n - 1), last = std::min(uint32_t(std::ceil(b)) - 1, n - 1);
        out[i * stride] =
            s.runEnd[first] >= last ? in[first * stride] : std::max(0.0, (integral(b) - integral(a)) / (b - a));
    }
}

// The 2-D box average of one channel plane (width x height, row-major): along rows, then along columns, which is
// the exact average over the clipped box because both the box and its clipping are separable.
void boxFilterPlane(std::vector<double>& plane, uint32_t width, uint32_t height, glm::dvec2 half, uint32_t threads) {
    std::vector<double> rows(plane.size());
    std::vector<LineScratch> scratch(resolveThreadCount(threads));
    parallelFor(height, threads, [&](uint32_t y, uint32_t worker) {
        boxFilterLine(plane.data() + size_t(y) * width, rows.data() + size_t(y) * width, 1, width, half.x,
                      scratch[worker]);
    });
    parallelFor(width, threads, [&](uint32_t x, uint32_t worker) {
        boxFilterLine(rows.data() + x, plane.data() + x, width, height, half.y, scratch[worker]);
    });
}

void checkInputs(const RasterBand& raster, const LandCoverParams& params, glm::dvec2 pixelSize,
                 const std::string& what) {
    require(raster.width >= 1 && raster.height >= 1 && raster.values.size() == size_t(raster.width) * raster.height,
            what + ": raster '" + raster.source + "' is empty");
    require(pixelSize.x > 0.0 && pixelSize.y > 0.0 && std::isfinite(pixelSize.x) && std::isfinite(pixelSize.y),
            what + ": the pixel size must be positive");
    require(params.borderWidth >= 0.0 && params.borderWidth <= kMaxLandCoverBorder,
            what + ": the border width must be 0.." + valueText(kMaxLandCoverBorder) + " m");
    require(params.table.channels == 3 || params.table.channels == 4, what + ": the table needs 3 or 4 channels");
}

} // namespace

GrassMap makeLandCoverGrassMap(const RasterBand& raster, const LandCoverParams& params, glm::dvec2 pixelSize,
                               const std::string& what, uint32_t threads) {
    checkInputs(raster, params, pixelSize, what);
    const ClassifiedRaster classes = classify(raster, params, what);
    const uint32_t channels = params.table.channels;
    const glm::dvec2 half = params.borderWidth * 0.5 / pixelSize; // in pixels
    std::vector<float> values(raster.values.size() * channels);
    std::vector<double> plane(raster.values.size());
    for (uint32_t c = 0; c < channels; ++c) {
        for (size_t i = 0; i < plane.size(); ++i) plane[i] = classes.intensities[classes.index[i]][int(c)];
        if (params.borderWidth > 0.0) boxFilterPlane(plane, raster.width, raster.height, half, threads);
        for (size_t i = 0; i < plane.size(); ++i) values[i * channels + c] = float(plane[i]);
    }
    return GrassMap(raster.width, raster.height, channels, std::move(values), raster.source);
}

GrassMap loadLandCoverGrassMap(const LandCoverParams& params, double tileSize, const std::string& what,
                               uint32_t threads, const InputFolders& folders) {
    RasterBand raster;
    try {
        raster = readRasterBand(params.file, {.band = params.band, .requireFinite = false, .folders = folders});
    } catch (const Error& e) {
        throw Error(what + ": " + e.what()); // which key named the file
    }
    const glm::dvec2 pixelSize(tileSize / raster.width, tileSize / raster.height);
    return makeLandCoverGrassMap(raster, params, pixelSize, what, threads);
}

GrassMap landCoverIntensityBound(const LandCoverParams& params) {
    const uint32_t channels = params.table.channels;
    std::vector<float> most(channels, 0.0f); // a nodata pixel without a class: zeros
    for (const auto& [code, intensities] : params.table.classes)
        for (uint32_t c = 0; c < channels; ++c) most[c] = std::max(most[c], intensities[int(c)]);
    return GrassMap(1, 1, channels, std::move(most), "the largest intensities of the land-cover table");
}

namespace {

std::string shortText(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}

// The box of pixel i along an axis of n pixels, in the raster's coordinates whatever window holds it: pixels
// first .. last, the first and the last covered for wFirst and wLast of their width, `length` pixels in all (the
// box clipped to the raster, as makeLandCoverGrassMap clips it).
struct AxisBox {
    uint32_t first = 0, last = 0;
    double wFirst = 1.0, wLast = 1.0, length = 1.0;
};

AxisBox axisBox(uint32_t i, uint32_t n, double half) {
    const double centre = double(i) + 0.5;
    const double a = std::max(0.0, centre - half), b = std::min(double(n), centre + half);
    AxisBox box{.first = std::min(uint32_t(a), n - 1), .last = std::min(uint32_t(std::ceil(b)) - 1, n - 1)};
    box.length = b - a;
    box.wFirst = box.first == box.last ? box.length : double(box.first + 1) - a;
    box.wLast = box.first == box.last ? box.length : b - double(box.last);
    return box;
}

// The box's pixels in up to three runs of one weight: the first pixel, the inner ones (weight 1), the last.
struct AxisRun {
    uint32_t first, last;
    double weight;
};

uint32_t axisRuns(const AxisBox& box, AxisRun runs[3]) {
    uint32_t count = 0;
    runs[count++] = {box.first, box.first, box.wFirst};
    if (box.last > box.first + 1) runs[count++] = {box.first + 1, box.last - 1, 1.0};
    if (box.last > box.first) runs[count++] = {box.last, box.last, box.wLast};
    return count;
}

// Counts of one class over rectangles of a window: a summed-area table of whole numbers, so a rectangle's count is
// exact and the same whichever window holds it.
class ClassCounts {
public:
    ClassCounts(const std::vector<uint32_t>& index, RasterWindow where) : where_(where) {
        sums_.resize(size_t(where.width + 1) * (where.height + 1));
        index_ = &index;
    }
    void build(uint32_t cls) {
        const size_t stride = where_.width + 1;
        for (uint32_t y = 0; y < where_.height; ++y) {
            uint32_t row = 0;
            for (uint32_t x = 0; x < where_.width; ++x) {
                row += (*index_)[size_t(y) * where_.width + x] == cls ? 1u : 0u;
                sums_[(y + 1) * stride + x + 1] = sums_[y * stride + x + 1] + row;
            }
        }
    }
    // Pixels of the class in raster columns x0..x1, rows y0..y1 (inside the window).
    uint32_t count(uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) const {
        const size_t stride = where_.width + 1;
        const size_t a = x0 - where_.column, b = x1 + 1 - where_.column, c = y0 - where_.row, d = y1 + 1 - where_.row;
        return sums_[d * stride + b] - sums_[c * stride + b] - sums_[d * stride + a] + sums_[c * stride + a];
    }

private:
    RasterWindow where_;
    const std::vector<uint32_t>* index_;
    std::vector<uint32_t> sums_;
};

bool contains(RasterWindow outer, RasterWindow inner) {
    return inner.column >= outer.column && inner.row >= outer.row &&
           uint64_t(inner.column) + inner.width <= uint64_t(outer.column) + outer.width &&
           uint64_t(inner.row) + inner.height <= uint64_t(outer.row) + outer.height;
}

} // namespace

GrassMap makeLandCoverWindowGrassMap(const RasterBand& window, RasterWindow where, glm::uvec2 rasterSize,
                                     RasterWindow out, const LandCoverParams& params, glm::dvec2 pixelSize,
                                     const std::string& what, uint32_t threads) {
    checkInputs(window, params, pixelSize, what);
    require(window.width == where.width && window.height == where.height &&
                contains(RasterWindow{0, 0, rasterSize.x, rasterSize.y}, where) && out.width >= 1 && out.height >= 1 &&
                contains(where, out),
            what + ": makeLandCoverWindowGrassMap: the windows do not nest");
    const glm::dvec2 half = params.borderWidth * 0.5 / pixelSize; // in pixels
    std::vector<AxisBox> xs(out.width), ys(out.height);
    for (uint32_t x = 0; x < out.width; ++x) xs[x] = axisBox(out.column + x, rasterSize.x, half.x);
    for (uint32_t y = 0; y < out.height; ++y) ys[y] = axisBox(out.row + y, rasterSize.y, half.y);
    require(contains(where, {xs.front().first, ys.front().first, xs.back().last - xs.front().first + 1,
                             ys.back().last - ys.front().first + 1}),
            what + ": makeLandCoverWindowGrassMap: the window lacks pixels the border reaches");
    const ClassifiedRaster classes = classify(window, params, what, {where.column, where.row});
    const uint32_t channels = params.table.channels;
    const size_t pixels = size_t(out.width) * out.height;
    std::vector<double> weighted(pixels * channels, 0.0); // sum over classes of intensity x covered area
    std::vector<int64_t> alone(pixels, -1);               // the class filling the pixel's box, if one does
    std::vector<bool> present(classes.intensities.size(), false);
    for (uint32_t i : classes.index) present[i] = true;
    ClassCounts counts(classes.index, where);
    // Class by class in table order, so every pixel's sum is added in the same order wherever it is computed.
    for (uint32_t cls = 0; cls < classes.intensities.size(); ++cls) {
        if (!present[cls]) continue;
        counts.build(cls);
        const glm::vec4 intensity = classes.intensities[cls];
        parallelFor(out.height, threads, [&](uint32_t y, uint32_t) {
            AxisRun rows[3], cols[3];
            const uint32_t rowRuns = axisRuns(ys[y], rows);
            for (uint32_t x = 0; x < out.width; ++x) {
                const AxisBox &bx = xs[x], &by = ys[y];
                const uint32_t inBox = counts.count(bx.first, bx.last, by.first, by.last);
                if (inBox == 0) continue;
                const size_t p = size_t(y) * out.width + x;
                if (uint64_t(inBox) == uint64_t(bx.last - bx.first + 1) * (by.last - by.first + 1)) {
                    alone[p] = cls;
                    continue;
                }
                const uint32_t colRuns = axisRuns(bx, cols);
                double area = 0.0;
                for (uint32_t r = 0; r < rowRuns; ++r)
                    for (uint32_t c = 0; c < colRuns; ++c)
                        area += rows[r].weight * cols[c].weight *
                                double(counts.count(cols[c].first, cols[c].last, rows[r].first, rows[r].last));
                for (uint32_t c = 0; c < channels; ++c) weighted[p * channels + c] += double(intensity[int(c)]) * area;
            }
        });
    }
    std::vector<float> values(pixels * channels);
    for (size_t p = 0; p < pixels; ++p) {
        const double area = xs[p % out.width].length * ys[p / out.width].length;
        for (uint32_t c = 0; c < channels; ++c)
            values[p * channels + c] = alone[p] >= 0 ? classes.intensities[size_t(alone[p])][int(c)]
                                                     : float(weighted[p * channels + c] / area);
    }
    return GrassMap(out.width, out.height, channels, std::move(values), window.source);
}

namespace {

// Pixels from a metric raster's west and south edges to the world's south-west corner: 0 without a projected origin
// (the raster starts there); else where the georeferencing of both puts it, on the raster's pixel grid.
glm::uvec2 projectedOffset(const RasterGeoTransform& geo, uint32_t height, const LandCoverWorld& world,
                           const std::string& what) {
    if (!world.projectedOrigin) return glm::uvec2(0);
    const glm::dvec2 southWest(geo.originX, geo.originY - double(height) * geo.pixelHeight);
    // Metres east / north of the raster's corner (the same coordinate system is assumed: GDAL's WKT is not compared).
    const glm::dvec2 metres = *world.projectedOrigin * world.metresPerUnit - southWest * geo.metresPerUnit;
    const glm::dvec2 pixels = metres / (glm::dvec2(geo.pixelWidth, geo.pixelHeight) * geo.metresPerUnit);
    const glm::dvec2 whole = glm::round(pixels);
    const glm::dvec2 off = glm::abs(pixels - whole) * glm::dvec2(geo.pixelWidth, geo.pixelHeight) * geo.metresPerUnit;
    require(glm::all(glm::lessThanEqual(off, glm::dvec2(world.tolerance + 1e-6))),
            what + ": the world's south-west corner lies " + shortText(pixels.x) + ", " + shortText(pixels.y) +
                " pixels from the raster's south-west corner, " + shortText(std::max(off.x, off.y)) +
                " m off its pixel grid (at most half a DEM sample, " + shortText(world.tolerance) +
                " m); resample it onto the DEM's (gdalwarp -tap, or -te from the world's corner)");
    require(whole.x >= 0.0 && whole.y >= 0.0,
            what + ": the world's south-west corner lies " + shortText(-metres.x) + " m west / " +
                shortText(-metres.y) +
                " m south of the raster's south-west corner (by their georeferencing): the "
                "land cover must cover the world's extent");
    return glm::uvec2(whole);
}

} // namespace

LandCoverGrid landCoverGrid(uint32_t width, uint32_t height, const std::optional<RasterGeoTransform>& geo,
                            const std::string& source, const LandCoverWorld& world, const std::string& what) {
    require(world.tilesX >= 1 && world.tilesY >= 1 && world.tileSize > 0.0, what + ": landCoverGrid: no world");
    const glm::dvec2 worldExtent(world.tilesX * world.tileSize, world.tilesY * world.tileSize);
    const std::string worldText = shortText(worldExtent.x) + " x " + shortText(worldExtent.y) + " m (" +
                                  std::to_string(world.tilesX) + " x " + std::to_string(world.tilesY) + " tiles of " +
                                  shortText(world.tileSize) + " m)";
    const std::string rasterText = "raster '" + source + "'";
    LandCoverGrid grid{.rasterSize = {width, height}};
    if (geo && geo->metresPerUnit > 0.0) {
        // Its own pixels, in metres: they must tile the world's tiles, and the raster reach over the whole world.
        const glm::dvec2 pixel = glm::dvec2(geo->pixelWidth, geo->pixelHeight) * geo->metresPerUnit;
        const glm::dvec2 perTile = world.tileSize / pixel, whole = glm::round(perTile);
        require(glm::all(glm::greaterThanEqual(whole, glm::dvec2(1.0))) &&
                    glm::all(glm::lessThanEqual(glm::abs(perTile - whole), 1e-6 * whole)),
                what + ": " + rasterText + " has pixels of " + shortText(pixel.x) + " x " + shortText(pixel.y) +
                    " m, which do not divide the world's tiles of " + shortText(world.tileSize) +
                    " m into whole pixels; resample it (gdalwarp -tr)");
        grid.pixelsPerTile = glm::uvec2(whole);
        grid.offset = projectedOffset(*geo, height, world, what + ": " + rasterText);
        const glm::dvec2 extent = glm::dvec2(width, height) * pixel;
        if (uint64_t(grid.offset.x) + uint64_t(world.tilesX) * grid.pixelsPerTile.x > width ||
            uint64_t(grid.offset.y) + uint64_t(world.tilesY) * grid.pixelsPerTile.y > height)
            throw Error(what + ": " + rasterText + " covers " + shortText(extent.x) + " x " + shortText(extent.y) +
                        " m (" + std::to_string(width) + " x " + std::to_string(height) + " pixels of " +
                        shortText(pixel.x) + " x " + shortText(pixel.y) + " m), but the world covers " + worldText +
                        ": in a world the land cover must cover the world's extent (" +
                        (world.projectedOrigin ? "where its georeferencing puts it" : "from its south-west corner") +
                        ")");
    } else {
        // Stretched over the world, as one tile's land cover is over its tile.
        require(width % world.tilesX == 0 && height % world.tilesY == 0,
                what + ": " + rasterText + " has " + std::to_string(width) + " x " + std::to_string(height) +
                    " pixels, not a whole number of pixels per tile of the world's " + worldText +
                    "; resample it to a multiple (gdalwarp -ts)");
        grid.pixelsPerTile = {width / world.tilesX, height / world.tilesY};
    }
    grid.pixelSize = world.tileSize / glm::dvec2(grid.pixelsPerTile);
    return grid;
}

namespace {

// The raster pixels of tile (x, y): tile 0 is the raster's south-west, tile rows count north, raster rows south.
RasterWindow tilePixels(const LandCoverGrid& grid, glm::uvec2 tile) {
    const glm::uvec2 ppt = grid.pixelsPerTile;
    require(uint64_t(grid.offset.x) + uint64_t(tile.x + 1) * ppt.x <= grid.rasterSize.x &&
                uint64_t(grid.offset.y) + uint64_t(tile.y + 1) * ppt.y <= grid.rasterSize.y,
            "land cover: the tile is outside the raster");
    return {grid.offset.x + tile.x * ppt.x, grid.rasterSize.y - grid.offset.y - (tile.y + 1) * ppt.y, ppt.x, ppt.y};
}

} // namespace

RasterWindow landCoverTileWindow(const LandCoverGrid& grid, glm::uvec2 tile, double borderWidth) {
    const RasterWindow pixels = tilePixels(grid, tile);
    // The box of a pixel reaches at most ceil(half) pixels beyond it; one more absorbs the rounding of its ends.
    const glm::dvec2 reach = glm::ceil(borderWidth * 0.5 / grid.pixelSize) + 1.0;
    const glm::uvec2 margin(std::min(reach.x, double(grid.rasterSize.x)), std::min(reach.y, double(grid.rasterSize.y)));
    const glm::uvec2 lo(pixels.column, pixels.row);
    const glm::uvec2 first = glm::uvec2(glm::max(glm::ivec2(lo) - glm::ivec2(margin), glm::ivec2(0)));
    const glm::uvec2 end = glm::min(lo + grid.pixelsPerTile + margin, grid.rasterSize);
    return {first.x, first.y, end.x - first.x, end.y - first.y};
}

GrassMap loadLandCoverTileGrassMap(const LandCoverParams& params, const LandCoverWorld& world, glm::uvec2 tile,
                                   const std::string& what, uint32_t threads, const InputFolders& folders) {
    const RasterReadOptions options{.band = params.band, .requireFinite = false, .folders = folders};
    try {
        const RasterInfo info = readRasterInfo(params.file, options);
        const LandCoverGrid grid = landCoverGrid(info.width, info.height, info.geoTransform, info.source, world, what);
        const RasterWindow where = landCoverTileWindow(grid, tile, params.borderWidth);
        const RasterBand window = readRasterWindow(params.file, where, options);
        return makeLandCoverWindowGrassMap(window, where, grid.rasterSize, tilePixels(grid, tile), params,
                                           grid.pixelSize, what, threads);
    } catch (const Error& e) {
        const std::string message = e.what();
        if (message.rfind(what, 0) == 0) throw;
        throw Error(what + ": " + message); // which key named the file
    }
}

GrassMap loadLandCoverPointGrassMap(const LandCoverParams& params, const LandCoverWorld& world, glm::dvec2 offset,
                                    double side, uint32_t resolution, const std::string& what,
                                    const InputFolders& folders) {
    require(resolution >= 1 && side > 0.0, what + ": loadLandCoverPointGrassMap: an empty map");
    const RasterReadOptions options{.band = params.band, .requireFinite = false, .folders = folders};
    try {
        const RasterInfo info = readRasterInfo(params.file, options);
        const LandCoverGrid grid = landCoverGrid(info.width, info.height, info.geoTransform, info.source, world, what);
        const uint32_t channels = params.table.channels;
        const double texel = side / resolution;
        // Each texel column's raster column, or none beyond the raster.
        std::vector<int64_t> columns(resolution);
        for (uint32_t c = 0; c < resolution; ++c) {
            const double x = std::floor((offset.x + (c + 0.5) * texel) / grid.pixelSize.x) + grid.offset.x;
            columns[c] = x >= 0.0 && x < grid.rasterSize.x ? int64_t(x) : -1;
        }
        std::vector<float> values(size_t(resolution) * resolution * channels, 0.0f);
        for (uint32_t r = 0; r < resolution; ++r) { // the top row is north
            const double y =
                std::floor((offset.y + (double(resolution - r) - 0.5) * texel) / grid.pixelSize.y) + grid.offset.y;
            if (!(y >= 0.0 && y < grid.rasterSize.y)) continue;
            const uint32_t row = grid.rasterSize.y - 1 - uint32_t(y);
            const RasterBand line = readRasterWindow(params.file, {0, row, grid.rasterSize.x, 1}, options);
            const ClassifiedRaster classes = classify(line, params, what, {0, row});
            for (uint32_t c = 0; c < resolution; ++c) {
                if (columns[c] < 0) continue;
                const glm::vec4 v = classes.intensities[classes.index[size_t(columns[c])]];
                for (uint32_t k = 0; k < channels; ++k) values[(size_t(r) * resolution + c) * channels + k] = v[int(k)];
            }
        }
        return GrassMap(resolution, resolution, channels, std::move(values), info.source);
    } catch (const Error& e) {
        const std::string message = e.what();
        if (message.rfind(what, 0) == 0) throw;
        throw Error(what + ": " + message); // which key named the file
    }
}

} // namespace sward
