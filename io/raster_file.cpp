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
// 320-byte GeoTIFF). A block may be as large as the largest raster sward reads, no larger.
void checkBlockSize(const std::string& path, GDALRasterBandH band) {
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
    const int64_t across = (GDALGetRasterBandXSize(band) + blockWidth - 1) / std::max(blockWidth, 1);
    const int64_t down = (GDALGetRasterBandYSize(band) + blockHeight - 1) / std::max(blockHeight, 1);
    for (int64_t y = 0; y < down; ++y)
        for (int64_t x = 0; x < across; ++x) {
            const std::string key = "BLOCK_SIZE_" + std::to_string(x) + "_" + std::to_string(y);
            const char* stored = GDALGetMetadataItem(band, key.c_str(), "TIFF");
            if (!stored) return; // not a TIFF
            require(std::strtoull(stored, nullptr, 10) <= fileBytes, "raster '" + path + "' claims a block of " +
                                                                         stored + " bytes in a file of " +
                                                                         std::to_string(fileBytes) + " (corrupt file)");
        }
}

} // namespace

RasterBand readRasterBand(const std::string& path, const RasterReadOptions& options) {
    checkLocalFile(path);
    registerDrivers();
    const RasterDoor door(path, options.folders); // outlives the dataset: GDAL reads through it until closed
    GdalMessages messages;                        // everything GDAL says until the dataset is closed
    Dataset dataset = openDataset(path, door, messages);
    GDALDatasetH ds = dataset.get();
    const int width = GDALGetRasterXSize(ds), height = GDALGetRasterYSize(ds);
    checkSize(path, width, height);
    GDALRasterBandH band = selectBand(ds, path, options.band);
    checkBlockSize(path, band);

    RasterBand raster;
    raster.width = uint32_t(width);
    raster.height = uint32_t(height);
    raster.source = path;
    raster.geoTransform = readGeoTransform(ds, path);
    raster.nodata = readNodata(band);
    raster.values.resize(size_t(width) * size_t(height));
    const CPLErr read =
        GDALRasterIO(band, GF_Read, 0, 0, width, height, raster.values.data(), width, height, GDT_Float64, 0, 0);
    require(door.refusal().empty(), door.refusal()); // a companion opened only for the pixels (an HFA .ige)
    require(read == CE_None, "cannot read raster '" + path + "' band " + std::to_string(options.band) +
                                 " (corrupt or truncated file)" + messages.suffix());
    if (options.requireFinite) checkFinite(raster, options.band);
    return raster;
}

} // namespace sward
