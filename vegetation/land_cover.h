// Land cover -> grass map (issue 15): a categorical raster of class codes (a GIS land-cover map such as ESA
// WorldCover) becomes a GrassMap through a table of grass-map channel intensities per class, with soft borders
// between classes.
//
// The raster covers the vegetation tile exactly, north up, like every grass map (grass_map.h): its georeferencing
// is not used, and the grass map has the raster's resolution. A pixel's intensities are the mean of the class
// intensities over the square of side `borderWidth` metres centred on it (clipped to the raster): across a straight
// border between two classes the intensities ramp linearly over `borderWidth`, centred on the border, and wherever
// that square holds a single class they are exactly that class's. The GrassMap then interpolates bilinearly
// between pixel centres, so a border narrower than a pixel looks like the one-pixel blend of a hard map.
// Deterministic: fixed summation order, no randomness, the same for any thread count.
#pragma once

#include "io/raster_file.h"
#include "vegetation/grass_map.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace sward {

// Class codes are whole numbers 0 .. kMaxLandCoverCode (every unsigned band type up to 32 bits).
inline constexpr int64_t kMaxLandCoverCode = 4294967295;
inline constexpr double kMaxLandCoverBorder = 1000.0; // metres
inline constexpr float kMaxLandCoverIntensity = 100.0f;

// Class code -> intensities of the grass-map channels R, G, B, A (R ferns / forest floor, G grass, B shrubs and
// flowers, A a fourth category; see VegetationParams::channelCategory). An intensity times the category's density
// is plants per m^2.
struct LandCoverTable {
    std::map<int64_t, glm::vec4> classes; // each intensity finite, 0 .. kMaxLandCoverIntensity
    uint32_t channels = 3;                // of the grass maps it makes: 3, or 4 when a class feeds A

    // The intensities of `code`, or nullptr when the table lacks it.
    const glm::vec4* find(int64_t code) const;
};

// The ESA WorldCover 2020 / 2021 legend (10 tree cover, 20 shrubland, 30 grassland, 40 cropland, 50 built-up,
// 60 bare / sparse vegetation, 70 snow and ice, 80 permanent water bodies, 90 herbaceous wetland, 95 mangroves,
// 100 moss and lichen) with intensities for sward's default categories; land_cover.cpp justifies each value and
// docs/scene-format.md lists them. WorldCover's "no data" (0) is not a class: nodata pixels, or a table entry.
LandCoverTable esaWorldCoverTable();

struct LandCoverParams {
    std::string file;  // the raster of class codes (any format io/raster_file.h reads)
    uint32_t band = 1; // the raster band holding the codes, from 1
    LandCoverTable table;
    double borderWidth = 5.0;          // metres, 0 .. kMaxLandCoverBorder; 0 = hard borders
    std::optional<int64_t> nodataCode; // the class the raster's nodata pixels count as; none: zero intensities
};

// The grass map of `raster`, whose pixels are pixelSize.x by pixelSize.y metres, on `threads` threads (0 = all
// cores). `what` names the input in errors ("scene.json: 'land_cover'"). Throws sward::Error for a value that is
// not a class code (not a whole number 0 .. kMaxLandCoverCode) and for a code missing from the table, naming the
// code, the raster and the pixel (x, y) of its first occurrence in row order; and for a nodata code not in the table.
GrassMap makeLandCoverGrassMap(const RasterBand& raster, const LandCoverParams& params, glm::dvec2 pixelSize,
                               const std::string& what, uint32_t threads = 0);

// Reads params.file (band params.band) and makes its grass map for a square tile of `tileSize` metres. The raster's
// errors (io/raster_file.h) are prefixed with `what`. Its companion files are read only inside `folders`.
GrassMap loadLandCoverGrassMap(const LandCoverParams& params, double tileSize, const std::string& what,
                               uint32_t threads = 0, const InputFolders& folders = {});

} // namespace sward
