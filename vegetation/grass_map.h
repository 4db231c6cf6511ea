// Grass map: a top-down image over one scene tile whose channels are vegetation densities (paper section 3.1).
//
// Each channel feeds one vegetation category (VegetationParams::channelCategory; by default R = ferns / forest
// floor, G = grass, B = shrubs and flowers); its intensity times the category density is plants per m^2.
// The map covers the tile exactly, north (+y) up: the top image row is the tile's north edge. Samples sit at
// pixel centres and are interpolated bilinearly, clamped to the edge pixels.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

class GrassMap {
public:
    GrassMap() = default;
    // values: width * height * channels intensities, row-major, top row first. Requires width, height >= 1,
    // channels 3 or 4, every value finite and >= 0 (throws sward::Error naming source otherwise).
    GrassMap(uint32_t width, uint32_t height, uint32_t channels, std::vector<float> values, std::string source);

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t channels() const { return channels_; }
    const std::string& source() const { return source_; }
    const std::vector<float>& values() const { return values_; }

    // Bilinear intensities at tile-relative uv in [0, 1]^2 (u east, v north); channels the map lacks read 0.
    glm::vec4 sample(glm::vec2 uv) const;
    // Mean intensity of one channel: exactly the integral of the bilinear reconstruction over the tile divided by
    // its area (with clamp-to-edge every pixel weighs the same), used to predict plant counts.
    double meanIntensity(uint32_t channel) const;

private:
    uint32_t width_ = 0, height_ = 0, channels_ = 0;
    std::vector<float> values_;
    std::string source_;
    std::vector<double> means_;
};

// Loads a grass map from an 8/16-bit RGB(A) PNG or an R,G,B[,A] float EXR. Throws sward::Error naming the file
// for a missing file, unsupported format or bit depth, a channel count other than 3 or 4, or a NaN, infinite or
// negative density.
GrassMap loadGrassMap(const std::string& path);

struct MeadowMapParams {
    uint32_t resolution = 512; // pixels per edge
    float tileSize = 500.0f;   // metres covered, sets the feature scale
    uint64_t seed = 1;
    glm::dvec2 origin{0.0};    // world xy of the tile's south-west corner (a world's tiles: one meadow across them)
};

// Procedural default map of the demo scene: a varied meadow that is mostly grass (G), with patches of ferns (R)
// where the grass thins, and small clusters of shrubs and flowers (B). A pure function of seed and world xy, so the
// maps of neighbouring tiles continue each other. Every intensity lies in [0, 1].
GrassMap makeMeadowGrassMap(const MeadowMapParams& params);

} // namespace sward
