// The atlas's structure: the cell grid, colour bleeding and the coverage-preserving mip chain. Painting the
// built-in atlas is in atlas_paint.cpp, reading and writing atlas files in atlas_file.cpp.
#include "vegetation/atlas.h"

#include "common/error.h"
#include "io/image_io.h"
#include "vegetation/atlas_colour.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace sward {

using atlas_detail::encodeSrgb;
using atlas_detail::encodeUnorm;
using atlas_detail::srgbTable;
using glm::vec3;
using glm::vec4;

// ---------------------------------------------------------------------------------------------------------------
// Layout

uint32_t AtlasDesc::maxColumns() const {
    size_t columns = 0;
    for (const AtlasRow& row : rows) columns = std::max(columns, row.cells.size());
    return uint32_t(columns);
}

uint32_t AtlasDesc::mipLevelCount() const {
    return uint32_t(std::bit_width(std::min(cellWidth, cellHeight)));
}

AtlasRect AtlasDesc::cellRect(uint32_t row, uint32_t column, uint32_t level) const {
    assert(row < rows.size() && column < maxColumns() && level < mipLevelCount());
    const uint32_t w = cellWidth >> level, h = cellHeight >> level;
    return {column * w, row * h, w, h};
}

std::array<float, 4> AtlasDesc::cellUvRect(uint32_t row, uint32_t column) const {
    const float cu = 1.0f / float(maxColumns()), cv = 1.0f / float(rows.size());
    return {float(column) * cu, float(row) * cv, float(column + 1) * cu, float(row + 1) * cv};
}

void validateAtlasDesc(const AtlasDesc& desc, const std::string& source) {
    require(std::has_single_bit(desc.cellWidth) && std::has_single_bit(desc.cellHeight) && desc.cellWidth >= 4 &&
                desc.cellHeight >= 4 && desc.cellWidth <= 4096 && desc.cellHeight <= 4096,
            source + ": atlas cell size " + std::to_string(desc.cellWidth) + "x" + std::to_string(desc.cellHeight) +
                " must be powers of two from 4 to 4096 (so every mip level keeps whole cells)");
    require(!desc.rows.empty() && desc.rows.size() <= 64, source + ": an atlas needs 1..64 rows");
    for (const AtlasRow& row : desc.rows)
        require(!row.cells.empty() && row.cells.size() <= 64,
                source + ": atlas row '" + row.category + "' must have 1..64 columns");
    require(uint64_t(desc.width()) <= kMaxImageEdge && uint64_t(desc.height()) <= kMaxImageEdge,
            source + ": atlas image would be " + std::to_string(desc.width()) + "x" + std::to_string(desc.height()) +
                " texels, more than " + std::to_string(kMaxImageEdge) + " per edge");
}

// ---------------------------------------------------------------------------------------------------------------
// Colour bleeding

namespace {

struct Rgba8View {
    uint8_t* data;
    uint32_t width;
    uint8_t* at(uint32_t x, uint32_t y) const { return data + (size_t(y) * width + x) * 4; }
};

void bleedCell(const Rgba8View& image, const AtlasRect& cell) {
    const uint32_t w = cell.width, h = cell.height;
    std::vector<uint32_t> distance(size_t(w) * h, UINT32_MAX);
    std::vector<uint32_t> queue;
    queue.reserve(distance.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if (image.at(cell.x + x, cell.y + y)[3] != 0) {
                distance[size_t(y) * w + x] = 0;
                queue.push_back(y * w + x);
            }
    if (queue.empty()) return; // nothing to bleed from; the cell's colour never shows
    // Breadth-first from the visible texels: a texel is reached only after every texel one step closer, so its
    // colour can be the mean of those neighbours. The result is smooth and depends only on the image.
    for (size_t head = 0; head < queue.size(); ++head) {
        const uint32_t x = queue[head] % w, y = queue[head] / w, d = distance[queue[head]];
        if (d > 0) {
            uint32_t sum[3] = {0, 0, 0}, count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = int(x) + dx, ny = int(y) + dy;
                    if (nx < 0 || ny < 0 || nx >= int(w) || ny >= int(h)) continue;
                    if (distance[size_t(ny) * w + size_t(nx)] != d - 1) continue;
                    const uint8_t* n = image.at(cell.x + uint32_t(nx), cell.y + uint32_t(ny));
                    for (int c = 0; c < 3; ++c) sum[c] += n[c];
                    ++count;
                }
            uint8_t* t = image.at(cell.x + x, cell.y + y);
            for (int c = 0; c < 3; ++c) t[c] = uint8_t((sum[c] + count / 2) / count);
        }
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = int(x) + dx, ny = int(y) + dy;
                if (nx < 0 || ny < 0 || nx >= int(w) || ny >= int(h)) continue;
                uint32_t& nd = distance[size_t(ny) * w + size_t(nx)];
                if (nd != UINT32_MAX) continue;
                nd = d + 1;
                queue.push_back(uint32_t(ny) * w + uint32_t(nx));
            }
    }
}

} // namespace

void bleedColours(Atlas& atlas) {
    require(!atlas.mips.empty(), "bleedColours: the atlas has no image");
    AtlasMip& image = atlas.mips[0];
    const Rgba8View view{image.rgba.data(), image.width};
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) bleedCell(view, atlas.desc.cellRect(r, c));
}

// ---------------------------------------------------------------------------------------------------------------
// Mipmaps

float alphaCoverage(const AtlasMip& mip, const AtlasRect& rect, float reference) {
    if (rect.width == 0 || rect.height == 0) return 0.0f;
    size_t passing = 0;
    for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
        for (uint32_t x = rect.x; x < rect.x + rect.width; ++x)
            passing += float(mip.rgba[(size_t(y) * mip.width + x) * 4 + 3]) / 255.0f >= reference;
    return float(passing) / float(size_t(rect.width) * rect.height);
}

uint32_t atlasLevelForTexel(uint32_t cellHeight, uint32_t levels, double plantHeight, double texelMetres) {
    if (!(plantHeight > 0.0) || levels == 0) return 0;
    // A level-l texel covers plantHeight * 2^l / cellHeight. Clamped as a double: an infinite ratio has no integer.
    const double ratio = texelMetres * double(cellHeight) / plantHeight;
    if (!(ratio >= 2.0)) return 0;
    return uint32_t(std::min(std::floor(std::log2(ratio)), double(levels - 1)));
}

std::array<float, 4> cardCover(const Atlas& atlas) {
    std::array<float, 4> cover{};
    const AtlasDesc& desc = atlas.desc;
    for (uint32_t r = 0; r < std::min<size_t>(desc.rows.size(), cover.size()); ++r) {
        double sum = 0.0;
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c)
            sum += double(desc.rows[r].cells[c].aspect) * alphaCoverage(atlas.mips.at(0), desc.cellRect(r, c, 0), 0.5f);
        cover[r] = float(sum / double(std::max<size_t>(desc.rows[r].cells.size(), 1)));
    }
    return cover;
}

std::array<float, 4> meanAspects(const AtlasDesc& desc) {
    std::array<float, 4> aspects{};
    for (uint32_t r = 0; r < std::min<size_t>(desc.rows.size(), aspects.size()); ++r) {
        double sum = 0.0;
        for (const AtlasCell& cell : desc.rows[r].cells) sum += double(cell.aspect);
        aspects[r] = float(sum / double(std::max<size_t>(desc.rows[r].cells.size(), 1)));
    }
    return aspects;
}

namespace {

// Fraction of alphas that pass the reference after scaling and 8-bit quantisation, exactly as alphaCoverage()
// will measure the stored level.
float scaledCoverage(const std::vector<float>& alphas, float scale, float reference) {
    size_t passing = 0;
    for (float a : alphas) passing += float(encodeUnorm(a * scale)) / 255.0f >= reference;
    return float(passing) / float(alphas.size());
}

// Alpha scale for one cell of one level that brings its coverage closest to `target` (bisection: coverage only
// grows with the scale).
float coverageScale(const std::vector<float>& alphas, float target, float reference) {
    if (target <= 0.0f) return 1.0f;
    float lo = 0.0f, hi = 1.0f;
    while (scaledCoverage(alphas, hi, reference) < target && hi < 1024.0f) lo = hi, hi *= 2.0f;
    for (int i = 0; i < 24; ++i) {
        const float mid = 0.5f * (lo + hi);
        (scaledCoverage(alphas, mid, reference) < target ? lo : hi) = mid;
    }
    const float below = scaledCoverage(alphas, lo, reference), above = scaledCoverage(alphas, hi, reference);
    const float best = std::min(target - below, above - target);
    // Many scales reach the same coverage; leave alpha alone when the level already matches as well as any scale
    // could (a solid cell stays solid instead of dropping to just above the reference).
    if (std::abs(scaledCoverage(alphas, 1.0f, reference) - target) <= best) return 1.0f;
    return target - below < above - target ? lo : hi;
}

} // namespace

void buildMipChain(Atlas& atlas, float alphaReference, bool preserveCoverage) {
    const AtlasDesc& desc = atlas.desc;
    require(!atlas.mips.empty() && atlas.mips[0].width == desc.width() && atlas.mips[0].height == desc.height() &&
                atlas.mips[0].rgba.size() == size_t(desc.width()) * desc.height() * 4,
            "buildMipChain: the atlas image does not match its description");
    atlas.mips.resize(1);
    const auto& toLinear = srgbTable().toLinear;

    // The chain is filtered from unscaled float levels; coverage scaling only touches the stored bytes, so one
    // level's scale never compounds into the next.
    uint32_t w = desc.width(), h = desc.height();
    std::vector<vec4> level(size_t(w) * h);
    for (size_t i = 0; i < level.size(); ++i) {
        const uint8_t* t = &atlas.mips[0].rgba[i * 4];
        level[i] = vec4(toLinear[t[0]], toLinear[t[1]], toLinear[t[2]], float(t[3]) / 255.0f);
    }

    const uint32_t columns = desc.maxColumns();
    for (uint32_t l = 1; l < desc.mipLevelCount(); ++l) {
        // Cells are powers of two and aligned, so a 2x2 box never straddles two cells.
        const uint32_t nw = w / 2, nh = h / 2;
        std::vector<vec4> next(size_t(nw) * nh);
        for (uint32_t y = 0; y < nh; ++y)
            for (uint32_t x = 0; x < nw; ++x) {
                const vec4 s[4] = {level[size_t(2 * y) * w + 2 * x], level[size_t(2 * y) * w + 2 * x + 1],
                                   level[size_t(2 * y + 1) * w + 2 * x], level[size_t(2 * y + 1) * w + 2 * x + 1]};
                vec3 weighted(0.0f), plain(0.0f);
                float alpha = 0.0f;
                for (const vec4& v : s) weighted += vec3(v) * v.a, plain += vec3(v), alpha += v.a;
                next[size_t(y) * nw + x] = vec4(alpha > 0.0f ? weighted / alpha : plain * 0.25f, alpha * 0.25f);
            }
        level = std::move(next);
        w = nw, h = nh;

        AtlasMip& mip = atlas.mips.emplace_back(AtlasMip{w, h, std::vector<uint8_t>(size_t(w) * h * 4)});
        for (uint32_t r = 0; r < desc.rows.size(); ++r)
            for (uint32_t c = 0; c < columns; ++c) {
                const AtlasRect cell = desc.cellRect(r, c, l);
                std::vector<float> alphas;
                alphas.reserve(size_t(cell.width) * cell.height);
                for (uint32_t y = cell.y; y < cell.y + cell.height; ++y)
                    for (uint32_t x = cell.x; x < cell.x + cell.width; ++x)
                        alphas.push_back(level[size_t(y) * w + x].a);
                const float target = alphaCoverage(atlas.mips[0], desc.cellRect(r, c, 0), alphaReference);
                const float scale = preserveCoverage ? coverageScale(alphas, target, alphaReference) : 1.0f;
                for (uint32_t y = cell.y; y < cell.y + cell.height; ++y)
                    for (uint32_t x = cell.x; x < cell.x + cell.width; ++x) {
                        const vec4& v = level[size_t(y) * w + x];
                        uint8_t* t = &mip.rgba[(size_t(y) * w + x) * 4];
                        for (int k = 0; k < 3; ++k) t[k] = encodeSrgb(v[k]);
                        t[3] = encodeUnorm(v.a * scale);
                    }
            }
    }
}

} // namespace sward
