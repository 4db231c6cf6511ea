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

std::string pixelText(const RasterBand& raster, size_t i) {
    return "(" + std::to_string(i % raster.width) + ", " + std::to_string(i / raster.width) + ")";
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

ClassifiedRaster classify(const RasterBand& raster, const LandCoverParams& params, const std::string& what) {
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
                        pixelText(raster, i) + ", which is not a class code (a whole number 0.." +
                        std::to_string(kMaxLandCoverCode) + ")");
        const auto it = indexOf.find(int64_t(v));
        if (it == indexOf.end())
            throw Error(what + ": class code " + std::to_string(int64_t(v)) + " of raster '" + raster.source +
                        "' (first at pixel " + pixelText(raster, i) + ") is not in the table (it has " +
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

} // namespace

GrassMap makeLandCoverGrassMap(const RasterBand& raster, const LandCoverParams& params, glm::dvec2 pixelSize,
                               const std::string& what, uint32_t threads) {
    require(raster.width >= 1 && raster.height >= 1 && raster.values.size() == size_t(raster.width) * raster.height,
            what + ": raster '" + raster.source + "' is empty");
    require(pixelSize.x > 0.0 && pixelSize.y > 0.0 && std::isfinite(pixelSize.x) && std::isfinite(pixelSize.y),
            what + ": the pixel size must be positive");
    require(params.borderWidth >= 0.0 && params.borderWidth <= kMaxLandCoverBorder,
            what + ": the border width must be 0.." + valueText(kMaxLandCoverBorder) + " m");
    require(params.table.channels == 3 || params.table.channels == 4, what + ": the table needs 3 or 4 channels");
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

} // namespace sward
