// DEM GeoTIFFs written with GDAL's own API for the GIS world tests (tests/scene/world_ground_test.cpp,
// tests/render/gis_world_test.cpp), and read back with it: the tests' independent view of the DEM.
#pragma once

#include <gdal.h>
#include <ogr_srs_api.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sward::test {

struct DemSpec {
    uint32_t columns = 0, rows = 0;
    double spacing = 1.0; // metres (a UTM zone) or degrees (epsg 4326)
    int epsg = 32633;     // WGS 84 / UTM 33N; 4326: geographic, in degrees
    std::optional<double> nodata;
    // Height of pixel (column, row), rows from the top (north). Unset: a sparse file whose blocks are written by
    // `blocks` only.
    std::function<double(uint32_t, uint32_t)> height;
    bool sparse = false; // tiled, SPARSE_OK: unwritten 256 x 256 blocks cost nothing
};

// Writes the DEM as a Float32 GeoTIFF, north up, its top-left corner at (500000, 4100000).
inline void writeDem(const std::string& path, const DemSpec& d) {
    GDALAllRegister();
    std::vector<const char*> options = {"TILED=YES", "COMPRESS=DEFLATE"};
    if (d.sparse) options.push_back("SPARSE_OK=TRUE");
    options.push_back(nullptr);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), int(d.columns), int(d.rows), 1,
                                 GDT_Float32, const_cast<char**>(options.data()));
    ASSERT_NE(ds, nullptr);
    double gt[6] = {500000.0, d.spacing, 0.0, 4100000.0, 0.0, -d.spacing};
    if (d.epsg == 4326) gt[0] = 14.0, gt[3] = 47.0;
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    ASSERT_EQ(OSRImportFromEPSG(srs, d.epsg), OGRERR_NONE);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (d.nodata) GDALSetRasterNoDataValue(band, *d.nodata);
    if (d.height) {
        std::vector<double> row(d.columns);
        for (uint32_t r = 0; r < d.rows; ++r) {
            for (uint32_t c = 0; c < d.columns; ++c) row[c] = d.height(c, r);
            ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, int(r), int(d.columns), 1, row.data(), int(d.columns), 1,
                                   GDT_Float64, 0, 0),
                      CE_None);
        }
    }
    GDALClose(ds);
}

// Writes `value` into the block of columns [x, x + w) and rows [y, y + h) of an existing DEM.
inline void writeDemBlock(const std::string& path, uint32_t x, uint32_t y, uint32_t w, uint32_t h,
                          const std::function<double(uint32_t, uint32_t)>& height) {
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_Update);
    ASSERT_NE(ds, nullptr);
    std::vector<double> values(size_t(w) * h);
    for (uint32_t r = 0; r < h; ++r)
        for (uint32_t c = 0; c < w; ++c) values[size_t(r) * w + c] = height(x + c, y + r);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, int(x), int(y), int(w), int(h), values.data(), int(w),
                           int(h), GDT_Float64, 0, 0),
              CE_None);
    GDALClose(ds);
}

// A small DEM's pixels as GDAL reads them, as floats (the file's Float32), row-major from the top row.
inline std::vector<float> readDemPixels(const std::string& path, uint32_t columns, uint32_t rows) {
    GDALAllRegister();
    std::vector<float> values(size_t(columns) * rows, NAN);
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    if (!ds) return values;
    if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, int(columns), int(rows), values.data(), int(columns),
                     int(rows), GDT_Float32, 0, 0) != CE_None)
        std::fill(values.begin(), values.end(), NAN);
    GDALClose(ds);
    return values;
}

} // namespace sward::test
