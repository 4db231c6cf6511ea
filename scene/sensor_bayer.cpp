#include "scene/sensor_bayer.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/sensor_model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>

namespace sward {

namespace {

// The tiles in reading order, indexed by BayerPattern - 1: the channel of pixel (x & 1, y & 1) is tile[2 (y & 1) + (x & 1)].
constexpr std::array<std::array<uint8_t, 4>, 4> kTiles = {{{0, 1, 1, 2}, {2, 1, 1, 0}, {1, 0, 2, 1}, {1, 2, 0, 1}}};
constexpr const char* kPatternNames[] = {"none", "RGGB", "BGGR", "GRBG", "GBRG"};

// One weight of an interpolation kernel, at (dx, dy) from the pixel, in eighths: every weight of both methods is a
// multiple of 1/16, so the sums below are exact in double for float inputs and only the final * 1/8 rounds (exactly,
// a power of two) before the conversion to float. A constant field therefore comes back bit for bit.
struct Tap {
    int8_t dx, dy;
    double eighths;
};
using Kernel = std::vector<Tap>;

// Which kernel a missing channel takes, by where the photosites of that colour lie around the pixel.
enum KernelKind { kGreenAtRedOrBlue, kFromLeftAndRight, kFromAboveAndBelow, kFromDiagonals, kKernelKinds };

// Bilinear: the mean of the 2 or 4 nearest photosites of the colour.
const std::array<Kernel, kKernelKinds> kBilinear = {{
    {{-1, 0, 2}, {1, 0, 2}, {0, -1, 2}, {0, 1, 2}},
    {{-1, 0, 4}, {1, 0, 4}},
    {{0, -1, 4}, {0, 1, 4}},
    {{-1, -1, 2}, {1, -1, 2}, {-1, 1, 2}, {1, 1, 2}},
}};

// Malvar, He and Cutler 2004, figure 2 (the coefficients times 8): bilinear plus a gain on the own channel's Laplacian.
const std::array<Kernel, kKernelKinds> kMalvar = {{
    {{0, 0, 4}, {-1, 0, 2}, {1, 0, 2}, {0, -1, 2}, {0, 1, 2}, {-2, 0, -1}, {2, 0, -1}, {0, -2, -1}, {0, 2, -1}},
    {{0, 0, 5},
     {-1, 0, 4},
     {1, 0, 4},
     {-2, 0, -1},
     {2, 0, -1},
     {-1, -1, -1},
     {1, -1, -1},
     {-1, 1, -1},
     {1, 1, -1},
     {0, -2, 0.5},
     {0, 2, 0.5}},
    {{0, 0, 5},
     {0, -1, 4},
     {0, 1, 4},
     {0, -2, -1},
     {0, 2, -1},
     {-1, -1, -1},
     {1, -1, -1},
     {-1, 1, -1},
     {1, 1, -1},
     {-2, 0, 0.5},
     {2, 0, 0.5}},
    {{0, 0, 6},
     {-1, -1, 2},
     {1, -1, 2},
     {-1, 1, 2},
     {1, 1, 2},
     {-2, 0, -1.5},
     {2, 0, -1.5},
     {0, -2, -1.5},
     {0, 2, -1.5}},
}};

// OpenCV's BORDER_REFLECT_101 (-1 -> 1, n -> n - 2), which keeps the parity and so the pattern; clamped for images
// narrower than the kernels.
int32_t reflect(int32_t i, int32_t n) {
    if (i < 0) i = -i;
    if (i >= n) i = 2 * (n - 1) - i;
    return std::clamp(i, 0, n - 1);
}

KernelKind kernelKind(BayerPattern pattern, uint32_t x, uint32_t y, uint32_t own, uint32_t missing) {
    if (missing == 1) return kGreenAtRedOrBlue;
    if (own != 1) return kFromDiagonals; // red at blue or blue at red
    return bayerChannel(pattern, x ^ 1u, y) == missing ? kFromLeftAndRight : kFromAboveAndBelow;
}

} // namespace

uint32_t bayerChannel(BayerPattern pattern, uint32_t x, uint32_t y) {
    require(pattern != BayerPattern::None, "bayerChannel: no colour filter array");
    return kTiles[size_t(pattern) - 1][(y & 1u) * 2 + (x & 1u)];
}

const char* bayerPatternName(BayerPattern pattern) {
    return kPatternNames[size_t(pattern)];
}

std::vector<float> bayerMosaic(BayerPattern pattern, uint32_t width, uint32_t height, std::span<const float> rgba) {
    require(rgba.size() == size_t(width) * height * 4, "bayerMosaic: image size does not match");
    std::vector<float> mosaic(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t p = size_t(y) * width + x;
            mosaic[p] = rgba[p * 4 + bayerChannel(pattern, x, y)];
        }
    return mosaic;
}

void demosaic(const ColourFilterArray& cfa, uint32_t width, uint32_t height, std::span<float> rgba) {
    require(cfa.enabled(), "demosaic: no colour filter array");
    const std::vector<float> mosaic = bayerMosaic(cfa.pattern, width, height, rgba);
    const std::array<Kernel, kKernelKinds>& kernels = cfa.demosaic == Demosaic::Malvar ? kMalvar : kBilinear;
    const int32_t w = int32_t(width), h = int32_t(height);
    for (int32_t y = 0; y < h; ++y)
        for (int32_t x = 0; x < w; ++x) {
            const size_t p = size_t(y) * width + uint32_t(x);
            const uint32_t own = bayerChannel(cfa.pattern, uint32_t(x), uint32_t(y));
            for (uint32_t c = 0; c < 3; ++c) {
                if (c == own) continue;
                double sum = 0.0;
                for (const Tap& t : kernels[kernelKind(cfa.pattern, uint32_t(x), uint32_t(y), own, c)])
                    sum += t.eighths *
                           double(mosaic[size_t(reflect(y + t.dy, h)) * width + uint32_t(reflect(x + t.dx, w))]);
                rgba[p * 4 + c] = float(sum * 0.125);
            }
        }
}

void parseColourFilterArray(JsonReader& reader, SensorParams& params) {
    const nlohmann::json* bayer = reader.raw("bayer");
    if (bayer && !bayer->is_null()) {
        const auto* name = bayer->is_string() ? bayer->get_ptr<const std::string*>() : nullptr;
        const auto* found = name ? std::find(std::begin(kPatternNames) + 1, std::end(kPatternNames), *name) : nullptr;
        if (!name || found == std::end(kPatternNames))
            reader.fail(reader.name("bayer") +
                        " must be null (a three-channel sensor), \"RGGB\", \"BGGR\", \"GRBG\" or \"GBRG\" (got " +
                        bayer->dump() + ")");
        params.cfa.pattern = BayerPattern(found - std::begin(kPatternNames));
        if (!params.enabled)
            reader.fail(reader.name("bayer") + " needs an enabled sensor (the sensor has 'enabled': false)");
    }
    if (reader.has("demosaic") && !params.cfa.enabled())
        reader.fail(reader.name("demosaic") + " needs a colour filter array ('bayer')");
    params.cfa.demosaic = Demosaic(reader.choice("demosaic", 0, {"bilinear", "malvar"}));
}

void colourFilterArrayToJson(const ColourFilterArray& cfa, nlohmann::json& json) {
    if (!cfa.enabled()) return;
    json["bayer"] = bayerPatternName(cfa.pattern);
    json["demosaic"] = cfa.demosaic == Demosaic::Malvar ? "malvar" : "bilinear";
}

} // namespace sward
