// readRasterBand, readRasterInfo and readRasterWindow in a build without GDAL (SWARD_WITH_GDAL=OFF;
// io/CMakeLists.txt compiles this file instead of raster_file.cpp and raster_door.cpp): every raster is refused with
// one error that names it, GDAL and the option.
// 16-bit PNG and float EXR heightfields and PNG grass maps are read without GDAL (io/image_io.h).
#include "io/raster_file.h"

#include "common/optional_components.h"

namespace sward {

RasterBand readRasterBand(const std::string& path, const RasterReadOptions&) {
    requireComponent(Component::Gdal, "raster '" + path + "'");
    return {}; // not reached: this build has no GDAL
}

RasterInfo readRasterInfo(const std::string& path, const RasterReadOptions&) {
    requireComponent(Component::Gdal, "raster '" + path + "'");
    return {};
}

RasterBand readRasterWindow(const std::string& path, const RasterWindow&, const RasterReadOptions&) {
    requireComponent(Component::Gdal, "raster '" + path + "'");
    return {};
}

} // namespace sward
