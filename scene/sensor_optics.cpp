#include "scene/sensor_optics.h"

#include "scene/sensor_model.h"

#include "common/error.h"
#include "common/half_float.h"
#include "common/json_reader.h"
#include "common/parallel_for.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sward {

namespace {

constexpr uint32_t kCocTile = 16; // tiles over which the gather's search radius is the largest circle near them
constexpr double kPi = 3.14159265358979323846;

// Lindeberg's discrete Gaussian of variance t = sigma^2: tap n is proportional to e^-t I_n(t); the common factor
// e^-t cancels in the normalisation, so the taps are the power series of I_n(t) = sum_k (t/2)^(2k+n) / (k! (k+n)!),
// each term from the last by one product and one quotient: identical on every IEEE machine.
std::vector<float> discreteGaussian(double sigma) {
    if (!(sigma > 0.0)) return {};
    const double t = sigma * sigma, half = 0.5 * t;
    const uint32_t radius = uint32_t(std::ceil(4.0 * sigma)) + 1;
    std::vector<double> taps(radius + 1);
    double leading = 1.0; // (t/2)^n / n!
    for (uint32_t n = 0; n <= radius; ++n) {
        if (n > 0) leading *= half / double(n);
        double term = leading, sum = 0.0;
        for (uint32_t k = 0; k < 400 && term > sum * 1e-18; ++k) {
            sum += term;
            term *= half * half / (double(k + 1) * double(k + 1 + n));
        }
        taps[n] = sum;
    }
    double total = taps[0];
    for (uint32_t n = 1; n <= radius; ++n) total += 2.0 * taps[n];
    std::vector<float> kernel(radius + 1);
    for (uint32_t n = 0; n <= radius; ++n) kernel[n] = float(taps[n] / total);
    return kernel;
}

// Radius of the image corner farthest from the principal point, in pixels.
double cornerRadius(const Intrinsics& in) {
    double farthest = 0.0;
    for (double u : {0.0, double(in.width)})
        for (double v : {0.0, double(in.height)})
            farthest = std::max(farthest, std::sqrt((u - in.cx) * (u - in.cx) + (v - in.cy) * (v - in.cy)));
    return farthest;
}

// Search radius of the gather per 16 x 16 tile: ceil(r + 0.5) of the largest capped radius in any tile whose pixels
// could reach this one. Only an optimisation: sources beyond their own reach add nothing, whatever the radius.
std::vector<int32_t> tileSearchRadii(const std::vector<float>& radius, uint32_t w, uint32_t h) {
    const uint32_t tilesX = (w + kCocTile - 1) / kCocTile, tilesY = (h + kCocTile - 1) / kCocTile;
    std::vector<float> tileMax(size_t(tilesX) * tilesY, 0.0f);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float& m = tileMax[size_t(y / kCocTile) * tilesX + x / kCocTile];
            m = std::max(m, radius[size_t(y) * w + x]);
        }
    const int32_t span = int32_t(std::ceil((kMaxCocRadiusPx + 0.5) / kCocTile));
    std::vector<int32_t> search(tileMax.size());
    for (int32_t ty = 0; ty < int32_t(tilesY); ++ty)
        for (int32_t tx = 0; tx < int32_t(tilesX); ++tx) {
            float m = 0.0f;
            for (int32_t uy = std::max(0, ty - span); uy <= std::min(int32_t(tilesY) - 1, ty + span); ++uy)
                for (int32_t ux = std::max(0, tx - span); ux <= std::min(int32_t(tilesX) - 1, tx + span); ++ux)
                    m = std::max(m, tileMax[size_t(uy) * tilesX + uint32_t(ux)]);
            search[size_t(ty) * tilesX + uint32_t(tx)] = int32_t(std::ceil(double(m) + 0.5));
        }
    return search;
}

// Bilinear sample of channel c at array position (sx, sy), edges clamped. Zero weights skip their texel, so an
// infinite neighbour cannot turn an exact sample into NaN.
float bilinear(const std::vector<float>& image, uint32_t w, uint32_t h, double sx, double sy, int c) {
    const double fx = std::floor(sx), fy = std::floor(sy);
    const float tx = float(sx - fx), ty = float(sy - fy);
    const int32_t i0 = int32_t(std::clamp(fx, -2.0, double(w))), j0 = int32_t(std::clamp(fy, -2.0, double(h)));
    auto texel = [&](int32_t i, int32_t j) {
        i = std::clamp<int32_t>(i, 0, int32_t(w) - 1);
        j = std::clamp<int32_t>(j, 0, int32_t(h) - 1);
        return image[(size_t(j) * w + uint32_t(i)) * 4 + c];
    };
    auto lerp = [](float a, float b, float t) { return t == 0.0f ? a : a * (1.0f - t) + b * t; };
    return lerp(lerp(texel(i0, j0), texel(i0 + 1, j0), tx), lerp(texel(i0, j0 + 1), texel(i0 + 1, j0 + 1), tx), ty);
}

// The depth-of-field gather's inputs: per source pixel its capped circle of confusion's radius, its depth (NaN as
// sky), 1 / its disc's area and its colour.
struct DefocusSources {
    uint32_t w = 0, h = 0;
    std::vector<float> radius, depth, invArea, colour;
};

// Distance of offset (dx, dy), |dx|, |dy| <= kMaxReach, from a table (sqrt is exact in IEEE, the table only saves it).
constexpr int32_t kMaxReach = int32_t(kMaxCocRadiusPx) + 2;
const std::vector<float>& offsetDistances() {
    static const std::vector<float> table = [] {
        std::vector<float> t(size_t(2 * kMaxReach + 1) * (2 * kMaxReach + 1));
        for (int32_t dy = -kMaxReach; dy <= kMaxReach; ++dy)
            for (int32_t dx = -kMaxReach; dx <= kMaxReach; ++dx)
                t[size_t(dy + kMaxReach) * (2 * kMaxReach + 1) + size_t(dx + kMaxReach)] =
                    std::sqrt(float(dx * dx + dy * dy));
        return t;
    }();
    return table;
}

// Output pixel (x, y) of the depth of field: the sources within `reach` in a fixed order (rows, then columns), each
// weighted by its disc's coverage of the pixel over its area (the foreground / background rule in the header).
// Offsets no disc can reach are skipped, so the sum does not depend on `reach` beyond the largest disc.
void gatherDefocus(const DefocusSources& s, uint32_t x, uint32_t y, int32_t reach, float* out) {
    const std::vector<float>& distances = offsetDistances();
    const size_t p = size_t(y) * s.w + x;
    const float rp = s.radius[p], dp = s.depth[p];
    double sum[4] = {0.0, 0.0, 0.0, 0.0}, weights = 0.0;
    bool others = false;
    for (int32_t dy = std::max(-reach, -int32_t(y)); dy <= std::min(reach, int32_t(s.h) - 1 - int32_t(y)); ++dy) {
        int32_t span = reach; // the disc of radius `reach`: nothing beyond it has coverage
        while (span * span + dy * dy > reach * reach) --span;
        const float* row = &distances[size_t(dy + kMaxReach) * (2 * kMaxReach + 1) + size_t(kMaxReach)];
        const size_t rowStart = size_t(int32_t(y) + dy) * s.w;
        for (int32_t dx = std::max(-span, -int32_t(x)); dx <= std::min(span, int32_t(s.w) - 1 - int32_t(x)); ++dx) {
            const size_t q = rowStart + size_t(int32_t(x) + dx);
            const float rq = s.radius[q];
            const float covering = s.depth[q] <= dp ? rq : std::min(rq, rp);
            const float coverage = std::min(covering + 0.5f - row[dx], 1.0f);
            if (!(coverage > 0.0f)) continue;
            const double weight = double(coverage) * s.invArea[q];
            for (int c = 0; c < 4; ++c) sum[c] += weight * s.colour[q * 4 + c];
            weights += weight;
            others = others || q != p;
        }
    }
    if (!others) return; // only its own disc: the value stays, bit for bit
    for (int c = 0; c < 4; ++c) out[c] = float(sum[c] / weights);
}

} // namespace

void parseLensOptics(JsonReader& r, LensOptics& o) {
    o.mtfSigmaPx = r.number("mtf_sigma_px", 0.0, 0.0, 5.0);
    o.apertureF = r.number("aperture_f", 0.0, 0.0, 64.0);
    if (o.apertureF > 0.0 && o.apertureF < 0.7)
        r.fail(r.name("aperture_f") + " must be 0 (a pinhole) or between 0.7 and 64 (got " + formatNumber(o.apertureF) +
               ")");
    if (r.has("focus_distance_m")) {
        o.focusDistanceM = r.number("focus_distance_m", 0.0, 0.0, 1e6);
        if (!(o.focusDistanceM > 0.0)) r.fail(r.name("focus_distance_m") + " must be greater than 0");
    } else if (o.apertureF > 0.0) {
        r.fail(r.name("focus_distance_m") + " is required when 'aperture_f' is greater than 0");
    }
    o.pixelSizeUm = r.number("pixel_size_um", 3.45, 0.5, 100.0);
    o.chromaticAberrationPx = r.number("chromatic_aberration_px", 0.0, -10.0, 10.0);
}

void lensOpticsToJson(const LensOptics& o, nlohmann::json& json) {
    if (!o.active()) return;
    json["mtf_sigma_px"] = o.mtfSigmaPx;
    json["aperture_f"] = o.apertureF;
    if (o.focusDistanceM > 0.0) json["focus_distance_m"] = o.focusDistanceM;
    json["pixel_size_um"] = o.pixelSizeUm;
    json["chromatic_aberration_px"] = o.chromaticAberrationPx;
}

void checkOptics(const LensOptics& o, const Intrinsics& in) {
    if (!(o.apertureF > 0.0)) return;
    const double focal = in.fx * o.pixelSizeUm * 1e-6;
    if (!(o.focusDistanceM > focal))
        throw Error("'focus_distance_m' (" + formatNumber(o.focusDistanceM) +
                    " m) must exceed the focal length fx * 'pixel_size_um' (" + formatNumber(focal) + " m)");
}

SensorOptics::SensorOptics(const SensorParams& params, const Intrinsics& in, uint32_t threads)
    : active_(params.enabled && params.optics.active()), width_(in.width), height_(in.height), threads_(threads),
      cx_(in.cx), cy_(in.cy) {
    if (!active_) return;
    const LensOptics& p = params.optics;
    checkOptics(p, in);
    if (p.apertureF > 0.0) {
        const double pitch = p.pixelSizeUm * 1e-6, focal = in.fx * pitch, aperture = focal / p.apertureF;
        focusM_ = p.focusDistanceM;
        cocRadiusAtInfinity_ = 0.5 * aperture * focal / ((focusM_ - focal) * pitch);
    }
    mtfKernel_ = discreteGaussian(p.mtfSigmaPx);
    if (p.chromaticAberrationPx != 0.0) {
        const double corner = cornerRadius(in);
        require(corner > 0.0, "sensor optics: invalid camera intrinsics");
        redScale_ = 1.0 + p.chromaticAberrationPx / corner;
        blueScale_ = 1.0 - p.chromaticAberrationPx / corner;
    }
}

double SensorOptics::cocRadiusPx(double depth) const {
    if (cocRadiusAtInfinity_ == 0.0) return 0.0;
    if (!(depth < INFINITY)) return cocRadiusAtInfinity_; // sky, or no depth at all: the limit d -> infinity
    return cocRadiusAtInfinity_ * std::abs(1.0 - focusM_ / depth);
}

void SensorOptics::apply(std::span<const float> depth, std::span<float> rgba) const {
    if (!active_) return;
    const size_t pixels = size_t(width_) * height_;
    require(rgba.size() == pixels * 4, "sensor optics: image size does not match the camera");
    if (cocRadiusAtInfinity_ > 0.0) {
        require(depth.size() == pixels, "sensor optics: depth size does not match the camera");
        depthOfField(depth, rgba);
    }
    if (!mtfKernel_.empty()) mtfBlur(rgba);
    if (redScale_ != 1.0) chromaticAberration(rgba);
}

void SensorOptics::applyHalf(std::span<const float> depth, std::span<uint16_t> rgbaHalf) const {
    if (!active_) return;
    std::vector<float> rgba(rgbaHalf.size());
    std::transform(rgbaHalf.begin(), rgbaHalf.end(), rgba.begin(), halfBitsToFloat);
    apply(depth, rgba);
    std::transform(rgba.begin(), rgba.end(), rgbaHalf.begin(), floatToHalfBits);
}

void SensorOptics::depthOfField(std::span<const float> depthIn, std::span<float> rgba) const {
    const size_t pixels = size_t(width_) * height_;
    DefocusSources sources{.w = width_, .h = height_};
    sources.radius.resize(pixels);
    sources.depth.resize(pixels);
    sources.invArea.resize(pixels);
    float largest = 0.0f;
    for (size_t p = 0; p < pixels; ++p) {
        sources.depth[p] = std::isnan(depthIn[p]) ? INFINITY : depthIn[p]; // NaN sorts as sky in the occlusion rule
        const double r = std::min(cocRadiusPx(depthIn[p]), kMaxCocRadiusPx);
        sources.radius[p] = float(r);
        sources.invArea[p] = float(1.0 / std::max(kPi * r * r, 1.0));
        largest = std::max(largest, sources.radius[p]);
    }
    if (largest < 0.5f) return; // no disc reaches a neighbour: every pixel keeps its value
    const std::vector<int32_t> search = tileSearchRadii(sources.radius, width_, height_);
    const uint32_t tilesX = (width_ + kCocTile - 1) / kCocTile;
    sources.colour.assign(rgba.begin(), rgba.end());
    parallelFor(height_, threads_, [&](uint32_t y, uint32_t) {
        for (uint32_t x = 0; x < width_; ++x) {
            const int32_t reach = search[size_t(y / kCocTile) * tilesX + x / kCocTile];
            gatherDefocus(sources, x, y, reach, &rgba[(size_t(y) * width_ + x) * 4]);
        }
    });
}

void SensorOptics::mtfBlur(std::span<float> rgba) const {
    const uint32_t w = width_, h = height_;
    const int32_t radius = int32_t(mtfKernel_.size()) - 1;
    const size_t rowFloats = size_t(w) * 4;
    std::vector<float> rows(rgba.size());
    // One pass along rows into `rows`, one along columns back into the image. Each output value sums its taps in one
    // order (-radius .. radius) from 0, tap by tap over the whole row, so the compiler may vectorise across the row
    // without reordering any value's sum; edges clamp to the border pixel.
    parallelFor(h, threads_, [&](uint32_t y, uint32_t) {
        const float* source = &rgba[size_t(y) * rowFloats];
        float* sum = &rows[size_t(y) * rowFloats];
        for (int32_t k = -radius; k <= radius; ++k) {
            const float weight = mtfKernel_[size_t(std::abs(k))];
            const int32_t lo = std::clamp(-k, 0, int32_t(w)), hi = std::clamp(int32_t(w) - k, lo, int32_t(w));
            for (int32_t x = 0; x < lo; ++x) // left border: the first pixel
                for (int c = 0; c < 4; ++c) sum[size_t(x) * 4 + c] += weight * source[c];
            const ptrdiff_t shift = ptrdiff_t(4) * k;
            for (ptrdiff_t i = ptrdiff_t(lo) * 4; i < ptrdiff_t(hi) * 4; ++i) sum[i] += weight * source[i + shift];
            for (int32_t x = hi; x < int32_t(w); ++x) // right border: the last pixel
                for (int c = 0; c < 4; ++c) sum[size_t(x) * 4 + c] += weight * source[rowFloats - 4 + size_t(c)];
        }
    });
    parallelFor(h, threads_, [&](uint32_t y, uint32_t) {
        float* sum = &rgba[size_t(y) * rowFloats];
        std::fill(sum, sum + rowFloats, 0.0f);
        for (int32_t k = -radius; k <= radius; ++k) {
            const float weight = mtfKernel_[size_t(std::abs(k))];
            const size_t yy = size_t(std::clamp<int32_t>(int32_t(y) + k, 0, int32_t(h) - 1));
            const float* source = &rows[yy * rowFloats];
            for (size_t i = 0; i < rowFloats; ++i) sum[i] += weight * source[i];
        }
    });
}

void SensorOptics::chromaticAberration(std::span<float> rgba) const {
    const uint32_t w = width_, h = height_;
    const std::vector<float> source(rgba.begin(), rgba.end());
    // Output pixel u shows red from the ideal image at c + (u - c) / scale: red is magnified by `scale`.
    parallelFor(h, threads_, [&](uint32_t y, uint32_t) {
        for (uint32_t x = 0; x < w; ++x) {
            const double u = x + 0.5 - cx_, v = y + 0.5 - cy_;
            const size_t p = size_t(y) * w + x;
            rgba[p * 4 + 0] = bilinear(source, w, h, cx_ + u / redScale_ - 0.5, cy_ + v / redScale_ - 0.5, 0);
            rgba[p * 4 + 2] = bilinear(source, w, h, cx_ + u / blueScale_ - 0.5, cy_ + v / blueScale_ - 0.5, 2);
        }
    });
}

} // namespace sward
