#include "world/heightfield.h"

#include "common/error.h"
#include "common/hash.h"
#include "common/noise.h"
#include "io/image_io.h"
#include "io/raster_file.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sward {

Heightfield::Heightfield(uint32_t columns, uint32_t rows, float spacing, glm::vec2 origin, std::vector<float> heights)
    : columns_(columns), rows_(rows), spacing_(spacing), origin_(origin), heights_(std::move(heights)) {
    require(columns >= 2 && rows >= 2, "heightfield needs at least 2x2 samples");
    require(spacing > 0.0f && std::isfinite(spacing), "heightfield spacing must be positive");
    require(heights_.size() == size_t(columns) * rows, "heightfield sample count does not match its size");
    for (float h : heights_) require(std::isfinite(h), "heightfield contains a non-finite height");
    auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
    minHeight_ = *lo;
    maxHeight_ = *hi;
}

double Heightfield::heightDouble(double x, double y) const {
    double u = std::clamp((x - origin_.x) / spacing_, 0.0, double(columns_ - 1));
    double v = std::clamp((y - origin_.y) / spacing_, 0.0, double(rows_ - 1));
    uint32_t i = std::min(uint32_t(u), columns_ - 2);
    uint32_t j = std::min(uint32_t(v), rows_ - 2);
    double fx = u - i, fy = v - j;
    double h00 = sample(i, j), h10 = sample(i + 1, j), h01 = sample(i, j + 1), h11 = sample(i + 1, j + 1);
    // The two triangles of the cell, split along the (i,j)-(i+1,j+1) diagonal as in the rendered mesh.
    if (fx >= fy) return h00 + fx * (h10 - h00) + fy * (h11 - h10);
    return h00 + fy * (h01 - h00) + fx * (h11 - h01);
}

float Heightfield::height(glm::vec2 xy) const {
    return float(heightDouble(xy.x, xy.y));
}

glm::vec3 Heightfield::normal(glm::vec2 xy) const {
    float u = std::clamp((xy.x - origin_.x) / spacing_, 0.0f, float(columns_ - 1));
    float v = std::clamp((xy.y - origin_.y) / spacing_, 0.0f, float(rows_ - 1));
    uint32_t i = std::min(uint32_t(u), columns_ - 2);
    uint32_t j = std::min(uint32_t(v), rows_ - 2);
    float h00 = sample(i, j), h10 = sample(i + 1, j), h01 = sample(i, j + 1), h11 = sample(i + 1, j + 1);
    float dx, dy;
    if (u - float(i) >= v - float(j)) {
        dx = h10 - h00;
        dy = h11 - h10;
    } else {
        dx = h11 - h01;
        dy = h01 - h00;
    }
    return glm::normalize(glm::vec3(-dx, -dy, spacing_));
}

glm::vec3 Heightfield::vertexNormal(uint32_t i, uint32_t j) const {
    uint32_t i0 = i > 0 ? i - 1 : i, i1 = std::min(i + 1, columns_ - 1);
    uint32_t j0 = j > 0 ? j - 1 : j, j1 = std::min(j + 1, rows_ - 1);
    float left = sample(i0, j), right = sample(i1, j), below = sample(i, j0), above = sample(i, j1);
    // Beyond an edge the skirt's sample, so the difference is central as in the neighbouring tile (bitwise: the same
    // samples, the same 2 * spacing).
    float across = float(i1 - i0), along = float(j1 - j0);
    if (i == 0 && !skirt_.west.empty()) left = skirt_.west[j], across += 1.0f;
    if (i == columns_ - 1 && !skirt_.east.empty()) right = skirt_.east[j], across += 1.0f;
    if (j == 0 && !skirt_.south.empty()) below = skirt_.south[i], along += 1.0f;
    if (j == rows_ - 1 && !skirt_.north.empty()) above = skirt_.north[i], along += 1.0f;
    float dx = (right - left) / (across * spacing_);
    float dy = (above - below) / (along * spacing_);
    return glm::normalize(glm::vec3(-dx, -dy, 1.0f));
}

void Heightfield::setSkirt(HeightfieldSkirt skirt) {
    auto check = [](const std::vector<float>& side, uint32_t length) {
        require(side.empty() || side.size() == length, "heightfield skirt: a side does not match its edge");
        for (float h : side) require(std::isfinite(h), "heightfield skirt: a non-finite height");
    };
    check(skirt.south, columns_), check(skirt.north, columns_), check(skirt.west, rows_), check(skirt.east, rows_);
    skirt_ = std::move(skirt);
}

std::optional<double> Heightfield::raycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const {
    glm::dvec2 lo(origin_), hi = lo + glm::dvec2(extent());
    auto above = [&](double t) {
        glm::dvec3 p = origin + t * direction;
        if (p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y) return 1.0; // no terrain outside the grid
        return p.z - heightDouble(p.x, p.y);
    };
    // March in steps well below a cell so no hill is stepped over, then bisect the sign change. The surface
    // is piecewise linear, so bisection converges to the exact intersection.
    const double step = spacing_ * 0.25;
    double t0 = 0.0, f0 = above(0.0);
    if (f0 <= 0.0) return 0.0;
    for (double t1 = step; t0 < maxDistance; t1 += step) {
        t1 = std::min(t1, maxDistance);
        double f1 = above(t1);
        if (f1 <= 0.0) {
            for (int k = 0; k < 64; ++k) {
                double tm = 0.5 * (t0 + t1);
                (above(tm) > 0.0 ? t0 : t1) = tm;
            }
            return 0.5 * (t0 + t1);
        }
        if (direction.z >= 0.0 && origin.z + t1 * direction.z > maxHeight_) break; // climbing above all terrain
        t0 = t1;
    }
    return std::nullopt;
}

namespace {

// Index of the world-wide lattice point at `origin` (one axis): origin must be a whole multiple of spacing.
int64_t latticeIndex(double origin, float spacing) {
    require(std::abs(origin) <= 1e8, "procedural terrain origin must lie within +-1e8 m");
    const double k = std::floor(origin / double(spacing) + 0.5);
    require(std::abs(k * double(spacing) - origin) <= 1e-6 * std::max(1.0, std::abs(origin)),
            "procedural terrain origin must be a whole multiple of the grid spacing");
    return int64_t(k);
}

} // namespace

Heightfield makeProceduralTerrain(const ProceduralTerrainParams& p) {
    require(p.size > 0.0f && p.spacing > 0.0f && p.size / p.spacing <= float(kMaxHeightfieldCells),
            "terrain size / spacing must be positive and give at most " + std::to_string(kMaxHeightfieldCells) +
                " cells per side");
    require(p.featureSize > 0.0f && std::isfinite(p.amplitude), "terrain feature size must be positive");
    uint32_t cells = uint32_t(std::lround(p.size / p.spacing));
    uint32_t n = cells + 1;
    // xy come from the lattice index alone (origin 0: exactly the single-tile terrain's x = i * spacing), so a
    // vertex on the edge of two tiles is evaluated at bitwise the same point by both.
    const int64_t firstX = latticeIndex(p.origin.x, p.spacing), firstY = latticeIndex(p.origin.y, p.spacing);
    std::vector<float> heights(size_t(n) * n);
    for (uint32_t j = 0; j < n; ++j) {
        for (uint32_t i = 0; i < n; ++i) {
            double x = double(firstX + i) * p.spacing, y = double(firstY + j) * p.spacing;
            double sum = 0.0, weight = 1.0, frequency = 1.0 / p.featureSize, norm = 0.0;
            for (uint32_t o = 0; o < p.octaves; ++o) {
                sum += weight * valueNoise(p.seed, o, x * frequency, y * frequency);
                norm += weight;
                weight *= 0.45;
                frequency *= 2.0;
            }
            heights[size_t(j) * n + i] = float(0.5 * p.amplitude * sum / norm);
        }
    }
    return Heightfield(n, n, p.spacing, glm::vec2(p.origin), std::move(heights));
}

namespace {

// Raster rows run north to south; grid rows south to north. height(i, row) -> heights[(rows - 1 - row) * columns + i].
template <typename Sample>
std::vector<float> gridHeights(const std::string& path, uint32_t width, uint32_t height, Sample sample,
                               float verticalScale, float heightOffset) {
    require(width >= 2 && height >= 2, "heightfield '" + path + "' must be at least 2x2 pixels");
    std::vector<float> heights(size_t(width) * height);
    for (uint32_t row = 0; row < height; ++row)
        for (uint32_t i = 0; i < width; ++i) {
            const double value = sample(i, row);
            if (!std::isfinite(value)) // not require(): its message would be built for every pixel
                throw Error("heightfield '" + path + "' has a non-finite or nodata sample at pixel (" +
                            std::to_string(i) + ", " + std::to_string(row) + ")");
            const float h = float(value) * verticalScale + heightOffset;
            if (!(std::abs(h) <= 1e6f))
                throw Error("heightfield '" + path + "' has a height beyond 1e6 m at pixel (" + std::to_string(i) +
                            ", " + std::to_string(row) + ")");
            heights[size_t(height - 1 - row) * width + i] = h;
        }
    return heights;
}

// A heightmap's ground costs far more than its file: about 96 bytes a sample (the float height, the ground mesh's
// 64-byte vertex on the host and again on the GPU, six indices a cell); an 8192^2 GeoTIFF of 0.3 MB took 6.2 GB and
// then VK_ERROR_OUT_OF_DEVICE_MEMORY. Checked once the size is known, before the heights are copied.
void requireHeightmapBudget(const std::string& path, uint32_t width, uint32_t height) {
    const uint64_t samples = uint64_t(width) * height;
    require(samples <= kMaxHeightfieldSamples,
            "heightfield '" + path + "' has " + std::to_string(width) + "x" + std::to_string(height) + " = " +
                std::to_string(samples) + " samples: its ground would take about " +
                std::to_string(samples * kHeightfieldBytesPerSample >> 20) + " MiB, over the limit of " +
                std::to_string(kMaxHeightfieldSamples) + " samples (4097x4097); resample it (gdalwarp -tr)");
}

} // namespace

float rasterSpacing(const std::optional<RasterGeoTransform>& geoTransform, const std::string& path, float spacing) {
    if (spacing > 0.0f) return spacing;
    require(geoTransform.has_value(), "heightfield '" + path + "' has no georeferencing: give its metres per pixel");
    const RasterGeoTransform& g = *geoTransform;
    require(g.metresPerUnit > 0.0, "heightfield '" + path +
                                       "' is not in a projected coordinate system (metres): "
                                       "give its metres per pixel, or reproject it (gdalwarp -t_srs EPSG:<UTM zone>)");
    require(std::abs(g.pixelWidth - g.pixelHeight) <= 1e-9 * g.pixelWidth,
            "heightfield '" + path +
                "' has non-square pixels; resample it (gdalwarp -tr) or give its metres per pixel");
    return float(g.pixelWidth * g.metresPerUnit);
}

bool heightfieldNeedsGdal(const std::string& path) {
    const std::string extension = lowerExtension(path);
    return extension != "png" && extension != "exr";
}

Heightfield loadHeightfield(const std::string& path, float verticalScale, float spacing, glm::vec2 origin,
                            float heightOffset, const InputFolders& folders) {
    require(spacing >= 0.0f && std::isfinite(spacing), "heightfield '" + path + "': spacing must not be negative");
    require(std::isfinite(verticalScale) && std::isfinite(heightOffset),
            "heightfield '" + path + "': vertical scale and offset must be finite");
    if (heightfieldNeedsGdal(path)) {
        RasterReadOptions options;
        options.folders = folders;
        const RasterBand raster = readRasterBand(path, options);
        requireHeightmapBudget(path, raster.width, raster.height);
        const float step = rasterSpacing(raster.geoTransform, path, spacing);
        std::vector<float> heights = gridHeights(
            path, raster.width, raster.height,
            [&](uint32_t i, uint32_t row) {
                const double v = raster.at(i, row);
                return raster.isNodata(v) ? std::numeric_limits<double>::quiet_NaN() : v;
            },
            verticalScale, heightOffset);
        return Heightfield(raster.width, raster.height, step, origin, std::move(heights));
    }
    require(spacing > 0.0f,
            "heightfield '" + path + "' is a PNG / EXR without georeferencing: give its metres per pixel");
    ImageData image = loadImage(path);
    requireHeightmapBudget(path, image.width, image.height);
    require(image.bitDepth != 8,
            "heightfield '" + path + "' is an 8-bit PNG; use a 16-bit PNG or a float EXR (8 bits give terraces)");
    require(image.channels == 1, "heightfield '" + path + "' has " + std::to_string(image.channels) +
                                     " channels; it must have exactly one (grey PNG, or a single/Y EXR channel)");
    std::vector<float> heights = gridHeights(
        path, image.width, image.height, [&](uint32_t i, uint32_t row) { return double(image.at(i, row, 0)); },
        verticalScale, heightOffset);
    return Heightfield(image.width, image.height, spacing, origin, std::move(heights));
}

} // namespace sward
