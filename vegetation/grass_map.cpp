#include "vegetation/grass_map.h"

#include "common/error.h"
#include "io/image_io.h"
#include "common/noise.h"

#include <algorithm>
#include <cmath>

namespace sward {

GrassMap::GrassMap(uint32_t width, uint32_t height, uint32_t channels, std::vector<float> values, std::string source)
    : width_(width), height_(height), channels_(channels), values_(std::move(values)), source_(std::move(source)) {
    require(width_ >= 1 && height_ >= 1, "grass map '" + source_ + "' is empty");
    require(channels_ == 3 || channels_ == 4,
            "grass map '" + source_ + "' has " + std::to_string(channels_) +
                " channel(s); it needs 3 (RGB) or 4 (RGBA), one density channel per vegetation category");
    require(values_.size() == size_t(width_) * height_ * channels_,
            "grass map '" + source_ + "': sample count does not match its size");
    means_.assign(channels_, 0.0);
    for (size_t i = 0; i < values_.size(); ++i) {
        const float v = values_[i];
        if (!(std::isfinite(v) && v >= 0.0f)) {
            const size_t pixel = i / channels_;
            throw Error("grass map '" + source_ + "' has an invalid density " +
                        (std::isnan(v) ? std::string("NaN") : std::to_string(v)) + " in channel " +
                        "RGBA"[i % channels_] + " at pixel (" + std::to_string(pixel % width_) + ", " +
                        std::to_string(pixel / width_) + "); densities must be finite and >= 0");
        }
        means_[i % channels_] += v;
    }
    for (double& m : means_) m /= double(width_) * height_;
}

glm::vec4 GrassMap::sample(glm::vec2 uv) const {
    // Pixel centres sit at (i + 0.5) / width; v grows north while image rows grow south.
    const float px = std::clamp(uv.x * float(width_) - 0.5f, 0.0f, float(width_ - 1));
    const float py = std::clamp((1.0f - uv.y) * float(height_) - 0.5f, 0.0f, float(height_ - 1));
    const uint32_t x0 = uint32_t(px), y0 = uint32_t(py);
    const uint32_t x1 = std::min(x0 + 1, width_ - 1), y1 = std::min(y0 + 1, height_ - 1);
    const float fx = px - float(x0), fy = py - float(y0);
    const float* r0 = values_.data() + size_t(y0) * width_ * channels_;
    const float* r1 = values_.data() + size_t(y1) * width_ * channels_;
    glm::vec4 result(0.0f);
    for (uint32_t c = 0; c < channels_; ++c) {
        const float a = r0[x0 * channels_ + c], b = r0[x1 * channels_ + c];
        const float d = r1[x0 * channels_ + c], e = r1[x1 * channels_ + c];
        const float top = a + (b - a) * fx, bottom = d + (e - d) * fx;
        result[int(c)] = top + (bottom - top) * fy;
    }
    return result;
}

double GrassMap::meanIntensity(uint32_t channel) const {
    return channel < channels_ ? means_[channel] : 0.0;
}

GrassMap loadGrassMap(const std::string& path) {
    ImageData image = loadImage(path);
    return GrassMap(image.width, image.height, image.channels, std::move(image.samples), path);
}

namespace {

double smoothstep(double lo, double hi, double x) {
    double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Fractal sum of value noise in about [-1, 1], lattice spacing `feature` metres.
double fbm(uint64_t seed, uint32_t layer, double x, double y, double feature, uint32_t octaves) {
    double sum = 0.0, weight = 1.0, norm = 0.0, f = 1.0 / feature;
    for (uint32_t o = 0; o < octaves; ++o) {
        sum += weight * valueNoise(seed, layer * 16 + o, x * f, y * f);
        norm += weight;
        weight *= 0.5;
        f *= 2.0;
    }
    return sum / norm;
}

} // namespace

GrassMap makeMeadowGrassMap(const MeadowMapParams& p) {
    require(p.resolution >= 1 && p.resolution <= kMaxImageEdge, "meadow grass map resolution must be 1..32768");
    require(p.tileSize > 0.0f && std::isfinite(p.tileSize), "meadow grass map tile size must be positive");
    const uint32_t n = p.resolution;
    std::vector<float> values(size_t(n) * n * 3);
    for (uint32_t row = 0; row < n; ++row) {
        for (uint32_t i = 0; i < n; ++i) {
            // World xy of the pixel centre (row 0 is north); origin 0 adds exactly nothing.
            const double x = p.origin.x + (i + 0.5) / n * p.tileSize, y = p.origin.y + (n - row - 0.5) / n * p.tileSize;
            // Ferns: large soft patches covering roughly a fifth of the meadow.
            const double fern = smoothstep(0.2, 0.45, fbm(p.seed, 0, x, y, 60.0, 3));
            // Shrubs and flowers: small clusters, a few metres across, scattered everywhere but in fern patches.
            const double flower = smoothstep(0.35, 0.6, fbm(p.seed, 1, x, y, 9.0, 2)) * (1.0 - 0.7 * fern);
            // Grass: dense nearly everywhere with gentle variation, thinning under ferns.
            const double grass = (0.75 + 0.25 * fbm(p.seed, 2, x, y, 25.0, 3)) * (1.0 - 0.6 * fern);
            float* px = values.data() + (size_t(row) * n + i) * 3;
            px[0] = float(fern);
            px[1] = float(std::clamp(grass, 0.0, 1.0));
            px[2] = float(flower);
        }
    }
    return GrassMap(n, n, 3, std::move(values), "procedural meadow (seed " + std::to_string(p.seed) + ")");
}

} // namespace sward
