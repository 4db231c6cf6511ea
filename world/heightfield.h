// Heightfield terrain: a regular grid of heights, triangulated exactly as it is rendered.
//
// Coordinates are metres, right-handed, Z up (x east, y north). Cell (i, j) spans
// [origin.x + i*spacing, +spacing] x [origin.y + j*spacing, +spacing] and is split along its (i,j)-(i+1,j+1)
// diagonal. height(), normal() and raycast() evaluate that very triangulation, so plants placed with
// height() sit exactly on the rendered surface and raycast() gives the analytic depth of a rendered pixel.
#pragma once

#include "common/input_file.h"
#include "io/raster_file.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sward {

// The samples just beyond a heightfield's edges (a world tile's neighbours' edge-adjacent samples), used only by
// vertexNormal: south and north hold `columns` samples (rows -1 and rows), west and east `rows` (columns -1 and
// columns). An empty side keeps one-sided differences there.
struct HeightfieldSkirt {
    std::vector<float> south, north, west, east;
};

class Heightfield {
public:
    Heightfield() = default;
    // heights: columns * rows values, row-major with x fastest. Requires columns, rows >= 2, spacing > 0.
    Heightfield(uint32_t columns, uint32_t rows, float spacing, glm::vec2 origin, std::vector<float> heights);

    uint32_t columns() const { return columns_; }
    uint32_t rows() const { return rows_; }
    float spacing() const { return spacing_; }
    glm::vec2 origin() const { return origin_; }
    glm::vec2 extent() const { return {spacing_ * float(columns_ - 1), spacing_ * float(rows_ - 1)}; }
    const std::vector<float>& heights() const { return heights_; }
    float sample(uint32_t i, uint32_t j) const { return heights_[size_t(j) * columns_ + i]; }
    float minHeight() const { return minHeight_; }
    float maxHeight() const { return maxHeight_; }

    // Height of the rendered surface at xy (clamped to the grid).
    float height(glm::vec2 xy) const;
    // Unit normal of the rendered triangle under xy (flat, as rasterised).
    glm::vec3 normal(glm::vec2 xy) const;
    // Smooth per-vertex normal (central differences, one-sided at an edge without skirt), used for shading.
    glm::vec3 vertexNormal(uint32_t i, uint32_t j) const;
    // Gives the edge vertices' normals the samples beyond them, so a tile's edge normals are bitwise its neighbour's.
    // Requires each side empty or of its edge's length, every sample finite.
    void setSkirt(HeightfieldSkirt skirt);
    const HeightfieldSkirt& skirt() const { return skirt_; }
    // Distance t along a unit-length ray to the first hit of the rendered surface, if any within maxDistance.
    std::optional<double> raycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const;

private:
    double heightDouble(double x, double y) const;

    uint32_t columns_ = 0, rows_ = 0;
    float spacing_ = 1.0f;
    glm::vec2 origin_{0.0f};
    std::vector<float> heights_;
    HeightfieldSkirt skirt_;
    float minHeight_ = 0.0f, maxHeight_ = 0.0f;
};

struct ProceduralTerrainParams {
    float size = 500.0f;        // square tile edge, metres
    float spacing = 2.0f;       // grid spacing, metres
    float amplitude = 12.0f;    // peak-to-peak height scale, metres
    float featureSize = 160.0f; // wavelength of the largest hills, metres
    uint32_t octaves = 4;
    uint64_t seed = 1;
    // World xy of the south-west vertex, a whole multiple of spacing: every tile of a world is a window on one
    // world-wide lattice, so neighbouring tiles share bitwise identical heights along their common edge.
    glm::dvec2 origin{0.0};
};

// A heightfield ground (a heightmap or the procedural terrain) has at most kMaxHeightfieldSamples samples, 4097x4097
// (4096 cells a side): each costs about kHeightfieldBytesPerSample bytes once meshed and uploaded (the float height,
// the 64-byte vertex on the host and the GPU, six indices a cell), about 1.5 GiB at the limit. 8000 procedural cells
// a side took 54 s and 10 GB for a 32x24 render; an 8192^2 heightmap VK_ERROR_OUT_OF_DEVICE_MEMORY.
inline constexpr uint32_t kMaxHeightfieldCells = 4096;
inline constexpr uint64_t kMaxHeightfieldSamples = uint64_t(kMaxHeightfieldCells + 1) * (kMaxHeightfieldCells + 1);
inline constexpr uint64_t kHeightfieldBytesPerSample = 96;

// Rolling hills from hashed value noise (fBm), a pure function of the lattice point: vertex (i, j) lies at
// origin + spacing * (i, j) and its height depends on nothing else. Uses only + - * and floor, never libm
// transcendentals, so the heights are bitwise identical on every x86-64 machine and compiler. Throws sward::Error
// for an origin that is not a whole multiple of spacing (within 1e-6 relative) or beyond +-1e8 m, and for more than
// kMaxHeightfieldCells cells a side.
Heightfield makeProceduralTerrain(const ProceduralTerrainParams& params);

// Loads a heightfield from a single-channel 16-bit PNG (height = sample / 65535 * verticalScale + heightOffset), a
// float OpenEXR or any single-band raster GDAL reads (io/raster_file.h; height = value * verticalScale +
// heightOffset). The image is a top-down map with north (+y) up: its top row is the grid's last row (largest y),
// and pixel (i, row) is the vertex at origin + spacing * (i, height - 1 - row). spacing 0 takes a GDAL raster's
// georeferencing (square pixels of a projected coordinate system, in metres). Throws sward::Error naming the file
// for a missing file, an unsupported format, an 8-bit PNG (too coarse: visible terraces), more than one channel,
// a non-finite or nodata height, a height beyond 1e6 m, more than kMaxHeightfieldSamples samples, and spacing 0
// without usable georeferencing. A GDAL raster's companion files are read only inside `folders`
// (RasterReadOptions::folders) and logged there.
Heightfield loadHeightfield(const std::string& path, float verticalScale, float spacing,
                            glm::vec2 origin = glm::vec2(0.0f), float heightOffset = 0.0f,
                            const InputFolders& folders = {});

// The sample spacing of the GDAL raster `path` in metres: `spacing` when positive, else its square pixels in a
// projected coordinate system. Throws sward::Error naming the file for no georeferencing, one in degrees (a
// geographic system) and non-square pixels.
float rasterSpacing(const std::optional<RasterGeoTransform>& geoTransform, const std::string& path, float spacing);

// True when loadHeightfield reads `path` through GDAL: every extension but .png and .exr (any case).
bool heightfieldNeedsGdal(const std::string& path);

} // namespace sward
