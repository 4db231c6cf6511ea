// Reading one band of a raster file through GDAL: GeoTIFF, PNG, Esri ASCII grid and the other local file formats
// listed in kRasterDrivers (land-cover maps, heightmaps). Images sward writes itself go through io/image_files.h;
// grass maps and 16-bit PNG / EXR heightfields through io/image_io.h.
//
// Only local files are read: a path starting with /vsi (GDAL's virtual file systems, /vsicurl/ among them) or one
// that is not a regular file is refused before GDAL sees it, and GDAL may only pick a driver of kRasterDrivers, none
// of which reaches the network or names other datasets (no VRT, WMS, ...). GDAL reads the raster and its companion
// files (.aux.xml, world files, .prj, .hdr, .ige, ...) through sward's door (io/raster_door.h), which confines,
// checks and logs each one. GDAL's own messages never reach stderr: they become part of the one sward::Error,
// which names the file.
#pragma once

#include "common/input_file.h"
#include "io/image_io.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sward {

// The GDAL drivers readRasterBand may use: file formats of gridded values that read nothing but local files.
inline constexpr const char* kRasterDrivers[] = {"GTiff",          "PNG",  "JPEG",  "GIF",  "BMP", "PNM",     "AAIGrid",
                                                 "GRASSASCIIGrid", "XYZ",  "EHdr",  "ENVI", "HFA", "USGSDEM", "SRTMHGT",
                                                 "GSAG",           "GSBG", "GS7BG", "ISG",  "RST", "BT"};

// Largest raster read: each edge at most kMaxRasterEdge pixels and at most kMaxRasterPixels pixels in all, checked
// from the header before any pixel is allocated, so a corrupt header cannot ask for more. The pixel budget prices
// the chain behind the read (8 bytes a pixel): a land cover adds its class index, box-filter planes, float grass
// map and far-band cover (an 8192x8192 one: 2.75 GB peak and 21 s on the tiny test scene); a heightmap's ground is
// priced on its own (world/heightfield.h, 2^24 samples). 16384x16384, a 1.2 MB deflate GeoTIFF, took 3.4 GB
// (heightmap) and 8.3 GB then std::bad_alloc (land cover).
inline constexpr uint32_t kMaxRasterEdge = kMaxImageEdge;
inline constexpr uint64_t kMaxRasterPixels = uint64_t(1) << 26;
// Largest storage block (TIFF strip or tile) of a raster, bytes: the largest raster's pixels at 8 bytes each. GDAL
// allocates a block whole, so a header claiming more is refused before GDAL reads it.
inline constexpr uint64_t kMaxRasterBlockBytes = kMaxRasterPixels * 8;

// A north-up georeferencing: world x = originX + (column + 0.5) * pixelWidth at a pixel centre, world y = originY -
// (row + 0.5) * pixelHeight (rows go south). Units are those of the file's coordinate system (metres in a projected
// one such as UTM, degrees in a geographic one).
struct RasterGeoTransform {
    double originX = 0.0, originY = 0.0;        // top-left corner of the top-left pixel
    double pixelWidth = 1.0, pixelHeight = 1.0; // > 0
    double metresPerUnit = 0.0; // a projected coordinate system's linear unit in metres; 0: geographic or unknown
};

struct RasterBand {
    uint32_t width = 0, height = 0;
    std::vector<double> values;   // width * height, row-major, top row first, as stored (no scale / offset)
    std::optional<double> nodata; // the band's nodata value, if it has one (may be NaN)
    std::optional<RasterGeoTransform> geoTransform; // absent when the file has no georeferencing
    std::string source;                             // the file name, for messages

    double at(uint32_t x, uint32_t y) const { return values[size_t(y) * width + x]; }
    // True for the band's nodata value (a NaN nodata matches every NaN).
    bool isNodata(double value) const {
        return nodata && (value == *nodata || (std::isnan(value) && std::isnan(*nodata)));
    }
};

struct RasterReadOptions {
    uint32_t band = 1;          // from 1, as GDAL counts
    bool requireFinite = false; // a NaN or infinite value that is not the nodata value is an error
    // Where the raster's companion files may be read from; every file GDAL opens is logged there, with the raster's
    // path as its owner (io/raster_door.h). Default: unconfined.
    InputFolders folders;
};

// What a raster's header says, without its pixels: enough to plan window reads of a raster far larger than memory.
struct RasterInfo {
    uint32_t width = 0, height = 0; // the whole raster; any size GDAL opens (edge and pixel limits apply to windows)
    std::optional<double> nodata;   // the band's nodata value, if it has one
    std::optional<RasterGeoTransform> geoTransform; // absent when the file has no georeferencing
    std::string source;                             // the file name, for messages
};

// Reads one band as doubles. In a build without GDAL (SWARD_WITH_GDAL=OFF, io/raster_file_absent.cpp) every call
// throws one sward::Error naming the file, GDAL and the option. Otherwise it throws one sward::Error naming the file
// for: a /vsi path, a missing file or one that is not a regular file, a companion file GDAL asks for outside options.folders or not a regular file, a file no
// driver of kRasterDrivers reads, a raster without bands, a band out of range, a complex band, an edge over
// kMaxRasterEdge or more than kMaxRasterPixels pixels, a rotated, sheared or south-up geotransform, a read error,
// and (requireFinite) a non-finite value, naming its pixel. Safe to call from any thread: reads through GDAL's door
// take turns (io/raster_door.h).
RasterBand readRasterBand(const std::string& path, const RasterReadOptions& options = {});

// The header of `path` and of band options.band: size, georeferencing and nodata, no pixels. The same door, drivers
// and refusals as readRasterBand, but for the size: a raster of any size is described (a world's DEM may be
// 20,000 x 20,000 samples and more). Throws sward::Error naming the file.
RasterInfo readRasterInfo(const std::string& path, const RasterReadOptions& options = {});

// A window of samples: columns column + i * step for i < width, rows row + j * step for j < height, rows counted from
// the top (north) as in the file. step > 1 picks every step-th sample exactly (no resampling): a coarse view of a far
// terrain whose samples are bitwise those of the full-resolution reads.
struct RasterWindow {
    uint32_t column = 0, row = 0;
    uint32_t width = 0, height = 0; // samples read, >= 1 each
    uint32_t step = 1;              // >= 1
};

// Reads one window of one band as doubles, through GDAL RasterIO: the same door, drivers and checks as
// readRasterBand, with kMaxRasterEdge and kMaxRasterPixels applied to the window (width x height samples) while the
// whole raster may be far larger; the storage blocks the window touches are checked as readRasterBand checks every
// block. The band's geoTransform is that of the window: its origin at the window's top-left sample's corner, its
// pixel size step times the file's. Also throws sward::Error naming the file and the window for a window that
// reaches beyond the raster, an empty window or step 0.
RasterBand readRasterWindow(const std::string& path, const RasterWindow& window, const RasterReadOptions& options = {});

} // namespace sward
