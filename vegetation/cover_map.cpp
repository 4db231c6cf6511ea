#include "vegetation/cover_map.h"

#include "common/error.h"
#include "vegetation/atlas_colour.h"

#include <algorithm>

namespace sward {

std::vector<CategoryLook> categoryLooks(const Atlas& atlas, const VegetationParams& params) {
    require(atlas.desc.rows.size() >= params.categoryCount && !atlas.mips.empty(),
            "the atlas needs a row per vegetation category");
    const AtlasMip& image = atlas.mips[0];
    std::vector<CategoryLook> looks(params.categoryCount);
    for (uint32_t c = 0; c < params.categoryCount; ++c) {
        const AtlasRow& row = atlas.desc.rows[c];
        const uint32_t columns = std::min(uint32_t(row.cells.size()), params.categories[c].variants);
        glm::dvec3 colour(0.0);
        double alpha = 0.0, aspect = 0.0;
        for (uint32_t column = 0; column < columns; ++column) {
            const AtlasRect r = atlas.desc.cellRect(c, column);
            for (uint32_t y = r.y; y < r.y + r.height; ++y)
                for (uint32_t x = r.x; x < r.x + r.width; ++x) {
                    const uint8_t* t = &image.rgba[(size_t(y) * image.width + x) * 4];
                    const double a = t[3] / 255.0;
                    const auto& lin = atlas_detail::srgbTable().toLinear;
                    colour += a * glm::dvec3(lin[t[0]], lin[t[1]], lin[t[2]]);
                    alpha += a;
                }
            aspect += row.cells[column].aspect;
        }
        const AtlasRect cell = atlas.desc.cellRect(c, 0);
        const double opaque = alpha / (double(columns) * cell.width * cell.height);
        const double height = params.categories[c].height;
        looks[c].colour = alpha > 0.0 ? glm::vec3(colour / alpha) : glm::vec3(0.0f);
        looks[c].area = height * height * (aspect / columns) * opaque;
    }
    return looks;
}

CoverMap makeCoverMap(const GrassMap& map, const Atlas& atlas, const VegetationParams& params) {
    return makeCoverMap(map, categoryLooks(atlas, params), params);
}

CoverMap makeCoverMap(const GrassMap& map, std::span<const CategoryLook> looks, const VegetationParams& params) {
    require(looks.size() >= params.categoryCount, "makeCoverMap: one look per vegetation category");
    CoverMap cover{.width = map.width(), .height = map.height(), .origin = params.worldOrigin, .size = params.tileSize};
    cover.texels.resize(size_t(map.width()) * map.height());
    const std::vector<float>& values = map.values();
    for (size_t texel = 0; texel < cover.texels.size(); ++texel) {
        glm::dvec3 colour(0.0);
        double area = 0.0;
        for (uint32_t channel = 0; channel < map.channels(); ++channel) {
            const int32_t c = params.channelCategory[channel];
            if (c == kUnusedChannel) continue;
            const double density =
                double(values[texel * map.channels() + channel]) * params.categories[size_t(c)].density *
                params.densityMultiplier;
            const double hidden = density * looks[size_t(c)].area;
            colour += hidden * glm::dvec3(looks[size_t(c)].colour);
            area += hidden;
        }
        cover.texels[texel] = area > 0.0 ? glm::vec4(glm::vec3(colour / area), float(area)) : glm::vec4(0.0f);
    }
    return cover;
}

} // namespace sward
