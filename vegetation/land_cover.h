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

// The largest intensity of each channel over the table's classes (a nodata pixel's zeros included): no box average
// exceeds it, so a 1 x 1 map of these values bounds the plants of any map the table makes (predictPlantCount).
GrassMap landCoverIntensityBound(const LandCoverParams& params);

// A land cover over a world of tiles (issue 51): the raster's south-west corner lies at the world's south-west
// corner, north up, and the raster covers the world's tilesX x tilesY tiles of tileSize metres; each tile's grass
// map is the raster's window over that tile, blurred with the margin its border needs, so that it equals the whole
// raster's map cut at the tile (the same plants whichever tile generates a border).
struct LandCoverWorld {
    uint32_t tilesX = 1, tilesY = 1;
    double tileSize = 0.0; // metres
    // The world's south-west corner in a georeferenced ground's projected coordinates (a DEM world: the DEM's
    // south-west sample plus world_origin - terrain.heightmap.origin) and their metres per unit. Absent: the world
    // has no georeferencing of its own (procedural ground, or a DEM without it).
    std::optional<glm::dvec2> projectedOrigin;
    double metresPerUnit = 1.0;
    // How far (metres) the corner may lie off the land cover's pixel grid and still take its nearest pixel corner: a
    // DEM's samples are its pixels' centres, half a sample off the grid of a land cover of the same area.
    double tolerance = 0.0;
};

// How a raster of rasterSize pixels lies over a world: pixelsPerTile whole pixels per tile along each axis, the
// world's south-west corner `offset` pixels from the raster's west and south edges.
struct LandCoverGrid {
    glm::uvec2 rasterSize{0}, pixelsPerTile{0}, offset{0};
    glm::dvec2 pixelSize{0.0}; // metres: tileSize / pixelsPerTile
};

// Lays a raster of width x height pixels with georeferencing `geo` over `world`. A raster georeferenced in metres (a
// projected system) keeps its own pixels, which must divide a tile into whole pixels (within 1e-6), and must reach
// over the whole world: where the world has a projected origin (a DEM world) the raster lies where its
// georeferencing puts it (the world's corner on its nearest pixel corner, within world.tolerance), else from the world's
// south-west corner (it may reach beyond: a larger area's raster, cut there). One without georeferencing or without a
// linear unit (geographic, unknown) is stretched over the world exactly, as one tile's land cover is over its tile,
// and needs whole pixels per tile (width a multiple of tilesX, height of tilesY). Throws sward::Error prefixed with
// `what` naming the raster `source` and both extents, its pixels, or the pixel and tile counts.
LandCoverGrid landCoverGrid(uint32_t width, uint32_t height, const std::optional<RasterGeoTransform>& geo,
                            const std::string& source, const LandCoverWorld& world, const std::string& what);

// The pixels of the raster a tile's map reads: the tile's pixels widened by the pixels the border's box reaches,
// clipped to the raster. Tile (x, y) counts y northwards (tile row 0 is the raster's bottom rows).
RasterWindow landCoverTileWindow(const LandCoverGrid& grid, glm::uvec2 tile, double borderWidth);

// The grass map of the raster pixels `out` (inside `where`), from `window`, the raster's pixels `where` of a raster
// of rasterSize pixels of pixelSize metres. Each pixel is the mean over the clipped box of side borderWidth of the
// class intensities, from exact integer counts of each class in the box: bitwise the same whatever window holds the
// box (a tile's map equals the whole raster's cut at the tile), within float rounding of makeLandCoverGrassMap, and
// exactly a class's intensities where the box holds that class alone. Errors as makeLandCoverGrassMap, their pixels
// in raster coordinates.
GrassMap makeLandCoverWindowGrassMap(const RasterBand& window, RasterWindow where, glm::uvec2 rasterSize,
                                     RasterWindow out, const LandCoverParams& params, glm::dvec2 pixelSize,
                                     const std::string& what, uint32_t threads = 0);

// The land cover's class intensities point-sampled (no border blur) at the centres of a resolution x resolution
// grass map over the square of `side` metres whose south-west corner lies `offset` metres from the world's south-west
// corner: the far cover of a coarse view of the world (a horizon ring), not a tile's map. Texels beyond the raster
// have zero intensities. Reads the raster row by row (readRasterWindow). Errors as loadLandCoverTileGrassMap.
GrassMap loadLandCoverPointGrassMap(const LandCoverParams& params, const LandCoverWorld& world, glm::dvec2 offset,
                                    double side, uint32_t resolution, const std::string& what,
                                    const InputFolders& folders = {});

// Reads params.file and makes the grass map of tile (x, y) of `world` (landCoverGrid, landCoverTileWindow,
// makeLandCoverWindowGrassMap). Errors as loadLandCoverGrassMap and landCoverGrid.
GrassMap loadLandCoverTileGrassMap(const LandCoverParams& params, const LandCoverWorld& world, glm::uvec2 tile,
                                   const std::string& what, uint32_t threads = 0, const InputFolders& folders = {});

} // namespace sward
