// GDAL's door to the file system (used by io/raster_file.cpp only): a GDAL virtual file system under the prefix
// "/vsisward/", through which readRasterBand opens every raster. GDAL opens companion files by itself (PAM's
// .aux.xml, world files, .prj, an EHdr .hdr, an HFA .img's .ige named by its content), so confining the path
// sward hands GDAL is not enough: each file GDAL asks for here must
// - resolve (symlinks and `..` followed) inside the allowed folders (the scene's folder and --allow-assets),
// - be the raster itself or of a companion kind of kRasterCompanionSuffixes,
// - be a regular file, checked with fstat on a descriptor opened O_NONBLOCK (a FIFO never blocks, /dev/zero is
//   refused),
// and it is logged in the folders' log (InputFolders::record), so the dataset's fingerprint hashes it. A refused
// file that exists is an error (RasterDoor::refusal); a file that does not exist is only absent to GDAL.
#pragma once

#include "common/input_file.h"

#include <mutex>
#include <string>

namespace sward {

// The companion files GDAL may read beside a raster (lower case suffixes of the file name).
inline constexpr const char* kRasterCompanionSuffixes[] = {
    ".aux.xml", ".aux", ".ovr",  ".rrd", ".msk",  ".ige", ".tfw", ".tifw", ".tiffw", ".wld", ".pgw", ".pngw", ".jgw",
    ".jpgw",    ".gfw", ".gifw", ".bpw", ".bmpw", ".prj", ".hdr", ".stx",  ".clr",   ".rdc", ".ref", ".imd",  ".rpb"};

// While a RasterDoor lives, GDAL's opens under "/vsisward/" are checked for the raster `path` against `folders`
// and logged with `path` as their owner. One door at a time in the process (the constructor waits for the last
// one to close), as GDAL's handler table is global.
class RasterDoor {
public:
    RasterDoor(const std::string& path, const InputFolders& folders);
    ~RasterDoor();
    RasterDoor(const RasterDoor&) = delete;
    RasterDoor& operator=(const RasterDoor&) = delete;

    // The name to hand GDAL: "/vsisward" + the raster's absolute path.
    const std::string& gdalPath() const { return gdalPath_; }
    // The first file GDAL asked for and the door refused, as one error sentence; "" when none.
    const std::string& refusal() const { return refusal_; }

private:
    std::unique_lock<std::mutex> lock_;
    std::string gdalPath_, refusal_;
};

} // namespace sward
