// Rasters GDAL reads (heightmaps, land cover) through readRasterBand and loadHeightfield, with GDAL's opens going
// through sward's door (io/raster_door.h) confined to the input's folder. The first byte picks the file name, so
// one corpus reaches several drivers (GTiff, AAIGrid, PNG, EHdr's .flt, ...): the drivers sniff content, but some
// only try a file of their extension.
#include "fuzz/fuzz_input.h"
#include "io/raster_file.h"
#include "world/heightfield.h"

#include <filesystem>
#include <iterator>

namespace {

constexpr const char* kNames[] = {"input.tif", "input.asc", "input.png", "input.flt", "input.img",
                                  "input.hgt", "input.grd", "input.bt",  "input.xyz", "input.dem"};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const char* name = kNames[data[0] % std::size(kNames)];
    const std::string path = sward::fuzz::inputFile(data + 1, size - 1, name);
    const sward::InputFolders folders =
        sward::InputFolders::confinedTo({std::filesystem::canonical(std::filesystem::path(path).parent_path())});
    sward::fuzz::expectOnlyErrors(
        [&] { sward::readRasterBand(path, {.band = 1, .requireFinite = false, .folders = folders}); });
    return sward::fuzz::expectOnlyErrors([&] { sward::loadHeightfield(path, 1.0f, 0.0f, {}, 0.0f, folders); });
}
