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
    // A map finer than kMaxCoverMapEdge is read in blocks of f x f texels (clipped at the far edges): a cover texel
    // of a 16384^2 map cost 16 bytes here and 8 more on the GPU (6 GB for a 64x48 render), for a colour seen from
    // beyond the far LOD limit. The cover is linear in the densities, so the block's mean densities give exactly
    // the block's mean hidden area and its area-weighted colour; f = 1 reads every texel as it is.
    const uint32_t f = std::max({1u, (map.width() + kMaxCoverMapEdge - 1) / kMaxCoverMapEdge,
                                 (map.height() + kMaxCoverMapEdge - 1) / kMaxCoverMapEdge});
    CoverMap cover{.width = (map.width() + f - 1) / f,
                   .height = (map.height() + f - 1) / f,
                   .origin = params.worldOrigin,
                   .size = params.tileSize};
    cover.texels.resize(size_t(cover.width) * cover.height);
    const bool materials =
        std::any_of(params.categories.begin(), params.categories.begin() + params.categoryCount,
                    [](const VegetationCategory& c) { return c.groundMaterial != kNoGroundMaterial; });
    if (materials) cover.groundWeights.resize(cover.texels.size());
    const std::vector<float>& values = map.values();
    const uint32_t channels = map.channels();
    std::vector<double> density(channels);
    for (uint32_t row = 0; row < cover.height; ++row)
        for (uint32_t column = 0; column < cover.width; ++column) {
            std::fill(density.begin(), density.end(), 0.0);
            const uint32_t y1 = std::min(map.height(), (row + 1) * f), x1 = std::min(map.width(), (column + 1) * f);
            for (uint32_t y = row * f; y < y1; ++y)
                for (uint32_t x = column * f; x < x1; ++x)
                    for (uint32_t channel = 0; channel < channels; ++channel)
                        density[channel] += double(values[(size_t(y) * map.width() + x) * channels + channel]);
            const double texels = double(y1 - row * f) * double(x1 - column * f);
            glm::dvec3 colour(0.0);
            glm::dvec4 weights(0.0);
            double area = 0.0;
            for (uint32_t channel = 0; channel < channels; ++channel) {
                const int32_t c = params.channelCategory[channel];
                if (c == kUnusedChannel) continue;
                const double mean = f == 1 ? density[channel] : density[channel] / texels;
                weights[c] += mean;
                const double hidden =
                    mean * params.categories[size_t(c)].density * params.densityMultiplier * looks[size_t(c)].area;
                colour += hidden * glm::dvec3(looks[size_t(c)].colour);
                area += hidden;
            }
            cover.texels[size_t(row) * cover.width + column] =
                area > 0.0 ? glm::vec4(glm::vec3(colour / area), float(area)) : glm::vec4(0.0f);
            if (materials)
                cover.groundWeights[size_t(row) * cover.width + column] = glm::min(glm::vec4(weights), glm::vec4(1.0f));
        }
    return cover;
}

} // namespace sward
