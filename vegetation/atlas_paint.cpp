// The built-in atlas: plants painted procedurally cell by cell (the painters are in atlas_plants.cpp), so the
// project needs no third-party textures.
#include "vegetation/atlas.h"

#include "common/error.h"
#include "common/noise.h"
#include "vegetation/atlas_paint.h"
#include "vegetation/vegetation_params.h"

#include <bit>
#include <cassert>

namespace sward {

namespace atlas_detail {
namespace {

// One cell being painted: premultiplied linear RGBA, composited "over" stroke by stroke.
class CellCanvas {
public:
    CellCanvas(uint32_t size, uint64_t grainSeed) : size_(size), grainSeed_(grainSeed), texels_(size_t(size) * size) {}

    uint32_t size() const { return size_; }
    const vec4& texel(uint32_t x, uint32_t y) const { return texels_[size_t(y) * size_ + x]; }

    void draw(const Stroke& stroke) {
        const size_t n = stroke.points.size();
        assert(n >= 2 && stroke.halfWidths.size() == n);
        vec2 lo(1e30f), hi(-1e30f);
        for (size_t i = 0; i < n; ++i) {
            lo = glm::min(lo, stroke.points[i] - stroke.halfWidths[i] - 1.0f);
            hi = glm::max(hi, stroke.points[i] + stroke.halfWidths[i] + 1.0f);
        }
        const int x0 = std::max(0, int(std::floor(lo.x))), y0 = std::max(0, int(std::floor(lo.y)));
        const int x1 = std::min(int(size_) - 1, int(hi.x)), y1 = std::min(int(size_) - 1, int(hi.y));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) shade(stroke, x, y);
    }

private:
    void shade(const Stroke& s, int x, int y) {
        const vec2 p(float(x) + 0.5f, float(y) + 0.5f);
        float coverage = 0.0f, t = 0.0f, lateral = 0.0f;
        const size_t segments = s.points.size() - 1;
        for (size_t i = 0; i < segments; ++i) {
            const vec2 a = s.points[i], ab = s.points[i + 1] - a, ap = p - a;
            const float len2 = glm::dot(ab, ab);
            const float h = len2 > 0.0f ? std::clamp(glm::dot(ap, ab) / len2, 0.0f, 1.0f) : 0.0f;
            const float dist = glm::length(ap - ab * h);
            const float hw = s.halfWidths[i] + (s.halfWidths[i + 1] - s.halfWidths[i]) * h;
            // Box-filtered edge: full coverage one half texel inside the edge, none one half texel outside; a
            // stroke thinner than a texel is capped at its width so hairlines fade instead of staying solid.
            const float c = std::clamp(hw + 0.5f - dist, 0.0f, std::min(2.0f * hw, 1.0f));
            if (c > coverage) {
                coverage = c;
                t = (float(i) + h) / float(segments);
                const float side = ab.x * ap.y - ab.y * ap.x >= 0.0f ? 1.0f : -1.0f;
                lateral = hw > 0.0f ? side * std::min(dist / hw, 1.0f) : 0.0f;
            }
        }
        if (coverage <= 0.0f) return;

        vec3 colour = glm::mix(s.base, s.tip, smoothstep(s.tipStart, 1.0f, t));
        colour *= 1.0f - s.shadeBase * (1.0f - smoothstep(0.0f, 0.45f, t));
        colour *= 1.0f + s.sideShade * lateral;
        colour *= 1.0f + s.midrib * std::max(0.0f, 1.0f - std::abs(lateral) * 3.0f);
        // A faint mottle (veins, dust, small lesions); low so that it reads as soft texture, not as edges.
        const float grain = float(valueNoise(grainSeed_, 0, double(p.x) / 4.0, double(p.y) / 4.0));
        colour = glm::clamp(colour * (1.0f + 0.035f * grain), 0.0f, 1.0f);

        vec4& dst = texels_[size_t(y) * size_ + size_t(x)];
        dst = vec4(colour * coverage, coverage) + dst * (1.0f - coverage);
    }

    uint32_t size_;
    uint64_t grainSeed_;
    std::vector<vec4> texels_;
};

// Scales a plant about its base point so that it stays `margin` texels inside the cell's top and sides: a cell
// never spills into its neighbours, and the empty border keeps bilinear filtering of small mips inside the cell.
void fitInCell(Plant& plant, float size, float margin) {
    const vec2 anchor(size * 0.5f, size);
    float scale = 1.0f;
    for (const Stroke& s : plant)
        for (size_t i = 0; i < s.points.size(); ++i) {
            const vec2 d = s.points[i] - anchor;
            const float hw = s.halfWidths[i];
            const float reachX = std::abs(d.x) + hw, reachY = -d.y + hw;
            if (reachX > 0.0f) scale = std::min(scale, (size * 0.5f - margin) / reachX);
            if (reachY > 0.0f) scale = std::min(scale, (size - margin) / reachY);
        }
    if (scale >= 1.0f) return;
    for (Stroke& s : plant) {
        for (vec2& p : s.points) p = anchor + (p - anchor) * scale;
        for (float& w : s.halfWidths) w *= scale;
    }
}

} // namespace
} // namespace atlas_detail

using namespace atlas_detail;

// ---------------------------------------------------------------------------------------------------------------
// Generation

AtlasPlantKind atlasPlantKindForCategory(const std::string& category) {
    std::string name = category;
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name.find("grass") != std::string::npos) return AtlasPlantKind::Grass;
    if (name.find("fern") != std::string::npos || name.find("forest") != std::string::npos)
        return AtlasPlantKind::Ferns;
    return AtlasPlantKind::Flowers;
}

std::vector<AtlasRowSpec> defaultAtlasRows(uint32_t variantsOverride) {
    const VegetationParams defaults;
    std::vector<AtlasRowSpec> rows;
    for (uint32_t i = 0; i < defaults.categoryCount; ++i) {
        const VegetationCategory& category = defaults.categories[i];
        rows.push_back({.category = category.name,
                        .kind = atlasPlantKindForCategory(category.name),
                        .columns = variantsOverride > 0 ? variantsOverride : category.variants});
    }
    return rows;
}

Atlas generateAtlas(const AtlasGenParams& params) {
    require(std::has_single_bit(params.cellSize) && params.cellSize >= 32 && params.cellSize <= 2048,
            "atlas cell size " + std::to_string(params.cellSize) + " must be a power of two from 32 to 2048");
    Atlas atlas;
    atlas.desc.cellWidth = atlas.desc.cellHeight = params.cellSize;
    for (const AtlasRowSpec& spec : params.rows) {
        require(spec.columns >= 1 && spec.columns <= 64, "atlas row '" + spec.category + "' has " +
                                                             std::to_string(spec.columns) +
                                                             " variants; it must have 1..64");
        atlas.desc.rows.push_back({.category = spec.category, .cells = std::vector<AtlasCell>(spec.columns)});
    }
    validateAtlasDesc(atlas.desc, "generated atlas");

    const AtlasDesc& desc = atlas.desc;
    AtlasMip& image = atlas.mips.emplace_back(AtlasMip{desc.width(), desc.height(), {}});
    image.rgba.assign(size_t(image.width) * image.height * 4, 0);
    const float S = float(params.cellSize);
    for (uint32_t r = 0; r < desc.rows.size(); ++r) {
        const AtlasPlantKind kind = params.rows[r].kind;
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c) {
            // Keyed by (seed, kind, variant), not by row index: reordering rows does not repaint the plants.
            const uint64_t key = hashKey({params.seed, 0x61746c6173ull /* "atlas" */, uint64_t(kind), c});
            Dice dice{HashStream{key}};
            Plant plant = kind == AtlasPlantKind::Grass   ? paintGrass(dice, S, c)
                          : kind == AtlasPlantKind::Ferns ? paintFerns(dice, S, c)
                                                          : paintFlowers(dice, S, c);
            fitInCell(plant, S, std::max(2.0f, S * 0.02f));
            CellCanvas canvas(params.cellSize, hashKey({key, 1}));
            for (const Stroke& stroke : plant) canvas.draw(stroke);

            const AtlasRect rect = desc.cellRect(r, c);
            for (uint32_t y = 0; y < rect.height; ++y)
                for (uint32_t x = 0; x < rect.width; ++x) {
                    const vec4 p = canvas.texel(x, y);
                    uint8_t* t = &image.rgba[((size_t(rect.y) + y) * image.width + rect.x + x) * 4];
                    const vec3 straight = p.a > 0.0f ? vec3(p) / p.a : vec3(0.0f);
                    for (int k = 0; k < 3; ++k) t[k] = encodeSrgb(straight[k]);
                    t[3] = encodeUnorm(p.a);
                }
        }
    }
    bleedColours(atlas);
    return atlas;
}

} // namespace sward
