#include "io/raster_file.h"

#include "common/error.h"
#include "common/input_file.h"
#include "io/raster_door.h"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace sward {

namespace {

// GDAL's messages while this object lives, collected instead of printed: GDAL's default handler writes "ERROR 4:
// ..." to stderr, and sward's tools print exactly one error line. GDAL keeps its handler stack per thread.
class GdalMessages {
public:
    GdalMessages() { CPLPushErrorHandlerEx(&collect, this); }
    ~GdalMessages() { CPLPopErrorHandler(); }
    GdalMessages(const GdalMessages&) = delete;
    GdalMessages& operator=(const GdalMessages&) = delete;

    // " (GDAL: first; second)", or "" when GDAL said nothing.
    std::string suffix() const {
        std::string text;
        for (const std::string& m : messages_) text += (text.empty() ? "" : "; ") + m;
        return text.empty() ? text : " (GDAL: " + text + ")";
    }

private:
    static void CPL_STDCALL collect(CPLErr level, CPLErrorNum, const char* message) {
        auto* self = static_cast<GdalMessages*>(CPLGetErrorHandlerUserData());
        // Debug output is noise; a few messages say what went wrong, more only repeat it.
        if (level < CE_Warning || !message || self->messages_.size() >= 3) return;
        std::string m(message);
        if (m.size() > 300) m = m.substr(0, 300) + "...";
        self->messages_.push_back(std::move(m));
    }

    std::vector<std::string> messages_;
};

void registerDrivers() {
    static std::once_flag once;
    std::call_once(once, [] {
        GdalMessages quiet; // a plugin that fails to load must not print
        GDALAllRegister();
    });
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(dataset); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

// Only a readable local regular file reaches GDAL: /vsi prefixes (/vsicurl/, /vsis3/, ...) and GDAL's
// "DRIVER:connection" strings name no such file.
void checkLocalFile(const std::string& path) {
    std::string prefix = path.substr(0, 4);
    for (char& c : prefix) c = char(std::tolower(static_cast<unsigned char>(c)));
    require(prefix != "/vsi",
            "raster '" + path + "': GDAL virtual file systems (/vsi...) are not read; name a local file");
    std::error_code ec;
    require(std::filesystem::exists(path, ec), "cannot open raster '" + path + "': file missing or unreadable");
    openInputFile(path, "raster"); // a FIFO or a device is refused here, without blocking
}

Dataset openDataset(const std::string& path, const RasterDoor& door, const GdalMessages& messages) {
    std::vector<const char*> drivers(std::begin(kRasterDrivers), std::end(kRasterDrivers));
    drivers.push_back(nullptr);
    Dataset dataset(GDALOpenEx(door.gdalPath().c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR,
                               drivers.data(), nullptr, nullptr));
    require(door.refusal().empty(), door.refusal());
    if (!dataset) {
        std::string formats;
        for (const char* d : kRasterDrivers) formats += (formats.empty() ? "" : ", ") + std::string(d);
        throw Error("raster '" + path + "' is not a raster file sward reads (GDAL drivers " + formats + ")" +
                    messages.suffix());
    }
    return dataset;
}

// The file's north-up georeferencing, if it has any. GDAL reports (0, 1, 0, 0, 0, 1) for "none" in some drivers.
std::optional<RasterGeoTransform> readGeoTransform(GDALDatasetH dataset, const std::string& path) {
    double gt[6] = {};
    GdalMessages ignored; // "no geotransform" is not an error
    if (GDALGetGeoTransform(dataset, gt) != CE_None) return std::nullopt;
    if (gt[0] == 0.0 && gt[1] == 1.0 && gt[2] == 0.0 && gt[3] == 0.0 && gt[4] == 0.0 && gt[5] == 1.0)
        return std::nullopt;
    auto text = [&] {
        std::string s;
        for (double v : gt) {
            char number[32];
            std::snprintf(number, sizeof(number), "%.10g", v);
            s += (s.empty() ? "" : ", ") + std::string(number);
        }
        return "(" + s + ")";
    };
    for (double v : gt) require(std::isfinite(v), "raster '" + path + "' has a non-finite geotransform " + text());
    require(gt[2] == 0.0 && gt[4] == 0.0, "raster '" + path + "' has a rotated or sheared geotransform " + text() +
                                              "; only north-up rasters are read (warp it first, e.g. gdalwarp)");
    require(gt[1] > 0.0 && gt[5] < 0.0,
            "raster '" + path + "' is not north up (geotransform " + text() + "); warp it first, e.g. gdalwarp");
    // Only a projected system has linear units; degrees of a geographic one are no distance on the ground.
    double metresPerUnit = 0.0;
    if (OGRSpatialReferenceH srs = GDALGetSpatialRef(dataset); srs && OSRIsProjected(srs))
        metresPerUnit = OSRGetLinearUnits(srs, nullptr);
    return RasterGeoTransform{
        .originX = gt[0], .originY = gt[3], .pixelWidth = gt[1], .pixelHeight = -gt[5], .metresPerUnit = metresPerUnit};
}

std::optional<double> readNodata(GDALRasterBandH band) {
    int has = 0;
    double value = 0.0;
    switch (GDALGetRasterDataType(band)) {
    case GDT_Int64:
        value = double(GDALGetRasterNoDataValueAsInt64(band, &has));
        break;
    case GDT_UInt64:
        value = double(GDALGetRasterNoDataValueAsUInt64(band, &has));
        break;
    default:
        value = GDALGetRasterNoDataValue(band, &has);
        break;
    }
    return has ? std::optional<double>(value) : std::nullopt;
}

GDALRasterBandH selectBand(GDALDatasetH dataset, const std::string& path, uint32_t index) {
    const int bands = GDALGetRasterCount(dataset);
    require(bands > 0, "raster '" + path + "' has no raster band");
    require(index >= 1 && index <= uint32_t(bands), "raster '" + path + "' has " + std::to_string(bands) +
                                                        " band(s); band " + std::to_string(index) +
                                                        " does not exist (bands count from 1)");
    GDALRasterBandH band = GDALGetRasterBand(dataset, int(index));
    require(band != nullptr, "raster '" + path + "': cannot read band " + std::to_string(index));
    require(!GDALDataTypeIsComplex(GDALGetRasterDataType(band)),
            "raster '" + path + "' band " + std::to_string(index) + " holds complex numbers; sward reads real values");
    return band;
}

void checkSize(const std::string& path, int width, int height) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    require(width >= 1 && height >= 1 && uint32_t(width) <= kMaxRasterEdge && uint32_t(height) <= kMaxRasterEdge,
            "raster '" + path + "' has size " + size + "; each edge must be 1.." + std::to_string(kMaxRasterEdge) +
                " pixels");
    require(uint64_t(width) * uint64_t(height) <= kMaxRasterPixels,
            "raster '" + path + "' has size " + size + ": " + std::to_string(uint64_t(width) * uint64_t(height)) +
                " pixels, over the limit of " + std::to_string(kMaxRasterPixels) + " (8192x8192)");
}

void checkFinite(const RasterBand& raster, uint32_t band) {
    for (size_t i = 0; i < raster.values.size(); ++i) {
        const double v = raster.values[i];
        if (std::isfinite(v) || raster.isNodata(v)) continue;
        const std::string value = std::isnan(v) ? "NaN" : v > 0 ? "inf" : "-inf";
        throw Error("raster '" + raster.source + "' band " + std::to_string(band) + " has the non-finite value " +
                    value + " at pixel (" + std::to_string(i % raster.width) + ", " + std::to_string(i / raster.width) +
                    ") that is not its nodata value");
    }
}

// GDAL reads a raster a block (a TIFF strip or tile) at a time and allocates the block whole: a small raster whose
// header claims a huge block would have GDAL allocate gigabytes before reading a pixel (fuzz_raster's finding, a
// 320-byte GeoTIFF). A block may be as large as the largest raster sward reads, no larger. Only the blocks holding
// columns [x0, x1) and rows [y0, y1) are read, so only theirs are checked (all of them for a whole raster).
void checkBlockSize(const std::string& path, GDALRasterBandH band, int x0, int y0, int x1, int y1) {
    int blockWidth = 0, blockHeight = 0;
    GDALGetBlockSize(band, &blockWidth, &blockHeight);
    const uint64_t bytes = uint64_t(std::max(blockWidth, 0)) * uint64_t(std::max(blockHeight, 0)) *
                           uint64_t(std::max(GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band)), 1));
    require(bytes <= kMaxRasterBlockBytes, "raster '" + path + "' stores its pixels in blocks of " +
                                               std::to_string(blockWidth) + "x" + std::to_string(blockHeight) + " (" +
                                               std::to_string(bytes) + " bytes), over the limit of " +
                                               std::to_string(kMaxRasterBlockBytes) + " bytes (corrupt file?)");
    // A TIFF block's stored size is read into a buffer of that size: none can be larger than the file.
    const uint64_t fileBytes = std::filesystem::file_size(path);
    blockWidth = std::max(blockWidth, 1), blockHeight = std::max(blockHeight, 1);
    for (int64_t y = y0 / blockHeight; y <= (y1 - 1) / blockHeight; ++y)
        for (int64_t x = x0 / blockWidth; x <= (x1 - 1) / blockWidth; ++x) {
            const std::string key = "BLOCK_SIZE_" + std::to_string(x) + "_" + std::to_string(y);
            const char* stored = GDALGetMetadataItem(band, key.c_str(), "TIFF");
            if (!stored) return; // not a TIFF
            require(std::strtoull(stored, nullptr, 10) <= fileBytes, "raster '" + path + "' claims a block of " +
                                                                         stored + " bytes in a file of " +
                                                                         std::to_string(fileBytes) + " (corrupt file)");
        }
}

// One band of a raster open through the door: the door outlives the dataset (GDAL reads through it until it is
// closed) and GDAL's messages are collected until then.
class OpenBand {
public:
    OpenBand(const std::string& path, const RasterReadOptions& options)
        : path_(path), door_(checked(path), options.folders) {
        dataset_ = openDataset(path, door_, messages_);
        width_ = GDALGetRasterXSize(dataset_.get());
        height_ = GDALGetRasterYSize(dataset_.get());
        band_ = selectBand(dataset_.get(), path, options.band);
    }

    int width() const { return width_; }
    int height() const { return height_; }
    GDALRasterBandH band() const { return band_; }

    RasterInfo info() const {
        return RasterInfo{.width = uint32_t(width_),
                          .height = uint32_t(height_),
                          .nodata = readNodata(band_),
                          .geoTransform = readGeoTransform(dataset_.get(), path_),
                          .source = path_};
    }

    // Columns [x, x + w) of rows [y, y + h) into `out` (w * h doubles, row-major).
    void read(int x, int y, int w, int h, double* out, const std::string& what) const {
        const CPLErr result = GDALRasterIO(band_, GF_Read, x, y, w, h, out, w, h, GDT_Float64, 0, 0);
        require(door_.refusal().empty(), door_.refusal()); // a companion opened only for the pixels (an HFA .ige)
        require(result == CE_None,
                "cannot read raster '" + path_ + "' " + what + " (corrupt or truncated file)" + messages_.suffix());
    }

private:
    // Only a local regular file reaches the door and GDAL.
    static const std::string& checked(const std::string& path) {
        checkLocalFile(path);
        registerDrivers();
        return path;
    }

    std::string path_;
    RasterDoor door_;
    GdalMessages messages_;
    Dataset dataset_;
    int width_ = 0, height_ = 0;
    GDALRasterBandH band_ = nullptr;
};

std::string windowText(const RasterWindow& w) {
    return "window of " + std::to_string(w.width) + "x" + std::to_string(w.height) + " samples at column " +
           std::to_string(w.column) + ", row " + std::to_string(w.row) +
           (w.step > 1 ? " every " + std::to_string(w.step) + " samples" : "");
}

// The window's samples, a row at a time for step > 1: GDAL's own decimation (a smaller buffer) would choose its
// samples by its resampling rule, not every step-th exactly.
void readWindowSamples(const OpenBand& open, const RasterWindow& w, uint64_t spanX, RasterBand& raster,
                       const std::string& what) {
    raster.values.resize(size_t(w.width) * size_t(w.height));
    if (w.step == 1) {
        open.read(int(w.column), int(w.row), int(w.width), int(w.height), raster.values.data(), what);
        return;
    }
    std::vector<double> row(spanX);
    for (uint32_t j = 0; j < w.height; ++j) {
        open.read(int(w.column), int(w.row + uint64_t(j) * w.step), int(spanX), 1, row.data(), what);
        for (uint32_t i = 0; i < w.width; ++i) raster.values[size_t(j) * w.width + i] = row[size_t(i) * w.step];
    }
}

} // namespace

RasterBand readRasterBand(const std::string& path, const RasterReadOptions& options) {
    const OpenBand open(path, options);
    checkSize(path, open.width(), open.height());
    checkBlockSize(path, open.band(), 0, 0, open.width(), open.height());
    const RasterInfo info = open.info();
    RasterBand raster{.width = info.width,
                      .height = info.height,
                      .nodata = info.nodata,
                      .geoTransform = info.geoTransform,
                      .source = path};
    raster.values.resize(size_t(raster.width) * size_t(raster.height));
    open.read(0, 0, open.width(), open.height(), raster.values.data(), "band " + std::to_string(options.band));
    if (options.requireFinite) checkFinite(raster, options.band);
    return raster;
}

RasterInfo readRasterInfo(const std::string& path, const RasterReadOptions& options) {
    const OpenBand open(path, options);
    require(open.width() >= 1 && open.height() >= 1, "raster '" + path + "' has no pixels");
    return open.info();
}

RasterBand readRasterWindow(const std::string& path, const RasterWindow& w, const RasterReadOptions& options) {
    const OpenBand open(path, options);
    const std::string window = windowText(w);
    require(w.width >= 1 && w.height >= 1 && w.step >= 1,
            "raster '" + path + "': the " + window + " is empty (width, height and step must be at least 1)");
    const uint64_t spanX = uint64_t(w.width - 1) * w.step + 1, spanY = uint64_t(w.height - 1) * w.step + 1;
    require(w.column + spanX <= uint64_t(open.width()) && w.row + spanY <= uint64_t(open.height()),
            "raster '" + path + "': the " + window + " reaches beyond its " + std::to_string(open.width()) + "x" +
                std::to_string(open.height()) + " samples");
    require(w.width <= kMaxRasterEdge && w.height <= kMaxRasterEdge && uint64_t(w.width) * w.height <= kMaxRasterPixels,
            "raster '" + path + "': the " + window + " is over the limit of " + std::to_string(kMaxRasterEdge) +
                " samples an edge and " + std::to_string(kMaxRasterPixels) + " in all (8192x8192)");
    checkBlockSize(path, open.band(), int(w.column), int(w.row), int(w.column + spanX), int(w.row + spanY));
    const RasterInfo info = open.info();
    RasterBand raster{
        .width = w.width, .height = w.height, .nodata = info.nodata, .geoTransform = info.geoTransform, .source = path};
    if (raster.geoTransform) {
        // Sample (i, j) of the window has its centre where the file's sample (column + i step, row + j step) has.
        RasterGeoTransform& g = *raster.geoTransform;
        g.originX += (double(w.column) + 0.5 - 0.5 * w.step) * g.pixelWidth;
        g.originY -= (double(w.row) + 0.5 - 0.5 * w.step) * g.pixelHeight;
        g.pixelWidth *= w.step;
        g.pixelHeight *= w.step;
    }
    readWindowSamples(open, w, spanX, raster, "band " + std::to_string(options.band) + " " + window);
    if (options.requireFinite) checkFinite(raster, options.band);
    return raster;
}

} // namespace sward
