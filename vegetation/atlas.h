// Vegetation texture atlas: a grid of plant billboards, one row per vegetation category (row index = category
// index in VegetationParams) and one column per variant. generateAtlas() paints the built-in atlas procedurally,
// so the project needs no third-party textures; loadAtlas() reads a user-supplied PNG + JSON pair instead.
//
// Image: 8-bit RGBA, sRGB colour, straight (not premultiplied) alpha, row 0 of the image at the top. Cell (r, c)
// covers texels [c * cell_w, (c + 1) * cell_w) x [r * cell_h, (r + 1) * cell_h). The image is exactly
// (max columns) * cell_w wide and rows * cell_h high; cells right of a short row are unused (transparent).
// Fully transparent texels carry the colour of nearby opaque ones ("colour bleeding"), so bilinear filtering and
// mipmapping never pull in dark fringes.
//
// JSON description (atlas.json), every key except "cell_size" and "rows" optional; unknown keys are errors:
//   {
//     "format": "sward-atlas", "version": 1,
//     "cell_size": [256, 256],          // cell width, height in texels: powers of two, 4..4096
//     "base_u": 0.5, "base_v": 1.0,     // defaults for every cell (below)
//     "aspect": 1.0,
//     "rows": [                         // top to bottom; row i = vegetation category i
//       {"category": "ferns", "columns": 4,
//        "cells": [{"base_u": 0.5, "base_v": 1.0, "aspect": 1.0}, ...]}   // optional, exactly "columns" entries
//     ]
//   }
// Per cell: base_u, base_v = where the plant's base (the point that sits on the ground) lies in the cell, in cell
// UV (0..1, v down, so base_v = 1 is the bottom edge); aspect = width / height of the billboard quad that shows the
// whole cell undistorted. A renderer places a quad of the plant's height h and width h * aspect so that the base
// point lands on the plant position, and maps it to cellUvRect().
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Where a plant stands in its cell and how wide its quad is; see the file comment.
struct AtlasCell {
    float baseU = 0.5f;
    float baseV = 1.0f;
    float aspect = 1.0f;

    bool operator==(const AtlasCell&) const = default;
};

struct AtlasRow {
    std::string category;         // the vegetation category this row shows, e.g. "grass"
    std::vector<AtlasCell> cells; // one per column (variant); at least one

    bool operator==(const AtlasRow&) const = default;
};

// A rectangle of texels in one mip level.
struct AtlasRect {
    uint32_t x = 0, y = 0, width = 0, height = 0;
};

struct AtlasDesc {
    uint32_t cellWidth = 256, cellHeight = 256; // texels at level 0
    std::vector<AtlasRow> rows;

    uint32_t maxColumns() const;
    uint32_t width() const { return maxColumns() * cellWidth; } // image size at level 0
    uint32_t height() const { return uint32_t(rows.size()) * cellHeight; }
    // Mip levels that keep every cell whole: log2(min(cellWidth, cellHeight)) + 1 (the last has 1-texel cells).
    uint32_t mipLevelCount() const;
    // Texels of cell (row, column) at a mip level. Precondition: row/column/level in range.
    AtlasRect cellRect(uint32_t row, uint32_t column, uint32_t level = 0) const;
    // Normalised UV rectangle {u0, v0, u1, v1} of cell (row, column), identical at every mip level.
    std::array<float, 4> cellUvRect(uint32_t row, uint32_t column) const;

    bool operator==(const AtlasDesc&) const = default;
};

// One mip level: width * height RGBA8 texels, row-major, top row first.
struct AtlasMip {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;

    bool operator==(const AtlasMip&) const = default;
};

// mips[0] is the full-resolution image; generateAtlas() and loadAtlas() return only that level, buildMipChain()
// appends the rest.
struct Atlas {
    AtlasDesc desc;
    std::vector<AtlasMip> mips;
};

// Throws sward::Error naming `source` unless the grid is one an atlas can have: cell sizes powers of two from 4 to
// 4096, 1..64 rows of 1..64 columns, an image of at most kMaxImageEdge texels per edge.
void validateAtlasDesc(const AtlasDesc& desc, const std::string& source);

// Which procedural painter fills a row.
enum class AtlasPlantKind {
    Grass,   // clumps of tapered, curved blades (some bent or broken), live greens mixed with dry, yellowed and
             // dead blades, every third clump with seed heads
    Ferns,   // green fronds with leaflets over a few dead leaves, each variant its own frond count, size and arch
    Flowers, // stems with small petalled heads (daisy, spike, cup) over leaf rosettes, and small flowering shrubs
};

struct AtlasRowSpec {
    std::string category;
    AtlasPlantKind kind = AtlasPlantKind::Grass;
    uint32_t columns = 4; // variants, 1..64
};

// Painter for a category name: "grass" -> Grass, "fern"/"forest" -> Ferns, anything else -> Flowers.
AtlasPlantKind atlasPlantKindForCategory(const std::string& category);

// Rows of the built-in atlas: the default categories of VegetationParams in order, with their variant counts
// (ferns 8, grass 12, flowers 8). variantsOverride > 0 gives every row that many columns instead.
std::vector<AtlasRowSpec> defaultAtlasRows(uint32_t variantsOverride = 0);

struct AtlasGenParams {
    uint64_t seed = 1;
    uint32_t cellSize = 256; // square cells; a power of two, 32..2048
    std::vector<AtlasRowSpec> rows = defaultAtlasRows();
};

// Paints the atlas (level 0 only, colour-bled). Deterministic: a pure function of params (hash-based randomness
// only), byte-identical on every run. Throws sward::Error for an invalid cell size, column count or image width.
Atlas generateAtlas(const AtlasGenParams& params);

// Fills the RGB of every fully transparent texel of mips[0] from the nearest non-transparent texels of the same
// cell (breadth-first, averaging the neighbours one step closer), leaving alpha and all other texels unchanged.
void bleedColours(Atlas& atlas);

// Replaces atlas.mips[1..] with desc.mipLevelCount() - 1 levels box-filtered per cell from mips[0]: a mip texel
// never mixes texels of two cells. Colour is averaged in linear light and weighted by alpha (straight alpha must
// not darken towards transparent texels). With preserveCoverage, each level's alpha is then scaled per cell so that
// the fraction of texels with alpha >= alphaReference matches level 0 (Castaño, "Computing alpha mipmaps", 2010):
// averaging thin blades with the transparent gaps between them pushes alpha below the alpha-test / alpha-to-
// coverage threshold, so without it grass thins out and vanishes with distance. preserveCoverage = false exists
// for comparison in tests.
void buildMipChain(Atlas& atlas, float alphaReference = 0.5f, bool preserveCoverage = true);

// Fraction (0..1) of the texels in rect whose alpha / 255 >= reference; 0 for an empty rect.
float alphaCoverage(const AtlasMip& mip, const AtlasRect& rect, float reference);

// Per row (category, up to 4): the mean over its cells of aspect * alphaCoverage(level 0, 0.5), the opaque area of
// the row's billboard per square metre of plant height (gpu::VegetationConstants::categoryCard; 0 for absent rows).
std::array<float, 4> cardCover(const Atlas& atlas);
// Per row (category, up to 4): the mean width / height of its cells (gpu::VegetationConstants::categoryAspect, far
// merging's estimate of a plant's width on screen; 0 for absent rows).
std::array<float, 4> meanAspects(const AtlasDesc& desc);

// The coarsest mip level whose texels are no larger than `texelMetres` on a plant `plantHeight` metres tall (a cell's
// `cellHeight` texels span the plant's height): 0 where even level 0 is coarser, at most `levels` - 1. The shadow
// pass reads its plants' alpha at this level for the cascade's texel (VegetationRenderer::shadowAtlasLevel).
uint32_t atlasLevelForTexel(uint32_t cellHeight, uint32_t levels, double plantHeight, double texelMetres);

// Reads an atlas PNG (8-bit RGBA) and its JSON description into mips[0]. Throws sward::Error naming the file for
// a missing or unreadable file, bad JSON or schema, a PNG that is not RGBA8, or an image size that does not match
// the JSON grid.
Atlas loadAtlas(const std::string& pngPath, const std::string& jsonPath);

// Writes mips[0] as PNG and the description as JSON (schema above), each atomically (common/atomic_file.h).
// Throws sward::Error naming the file if it cannot be written.
void saveAtlas(const Atlas& atlas, const std::string& pngPath, const std::string& jsonPath);

} // namespace sward
