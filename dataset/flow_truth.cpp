#include "dataset/flow_truth.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sward {

namespace {

// The one or two pixel centres (indices) around continuous coordinate `q` (pixel centres at +0.5), clamped.
uint32_t centresAround(double q, uint32_t size, uint32_t out[2]) {
    const double below = std::floor(q - 0.5);
    out[0] = uint32_t(std::clamp(below, 0.0, double(size - 1)));
    if (q - 0.5 == below) return 1; // on a centre: that centre's ray alone
    out[1] = uint32_t(std::clamp(below + 1.0, 0.0, double(size - 1)));
    return 2;
}

Visibility visibilityAt(uint32_t width, uint32_t height, double x, double y, double depth,
                        std::span<const float> targetDepth) {
    if (!(depth > 0.0) || !(x >= 0.0 && x <= width && y >= 0.0 && y <= height)) return Visibility::Occluded;
    uint32_t xs[2], ys[2];
    const uint32_t nx = centresAround(x, width, xs), ny = centresAround(y, height, ys);
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const double seen = targetDepth[size_t(ys[j]) * width + xs[i]];
            if (!(seen < depth * (1.0 - kFlowOcclusionTolerance))) return Visibility::Visible; // sky is never nearer
        }
    return Visibility::Occluded;
}

} // namespace

FlowTruth flowTruth(uint32_t width, uint32_t height, std::span<const float> flow, std::span<const float> targetDepth) {
    const size_t pixels = size_t(width) * height;
    require(flow.size() == 4 * pixels && targetDepth.size() == pixels, "flowTruth: image sizes differ");
    FlowTruth truth{.flow = {width, height, std::vector<float>(2 * pixels)},
                    .exr = std::vector<float>(3 * pixels),
                    .visibility = std::vector<Visibility>(pixels, Visibility::NoTruth)};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            const float* f = flow.data() + 4 * i;
            const bool surface = f[3] != 0.0f;
            truth.flow.uv[2 * i] = surface ? f[0] : std::numeric_limits<float>::quiet_NaN();
            truth.flow.uv[2 * i + 1] = surface ? f[1] : std::numeric_limits<float>::quiet_NaN();
            truth.exr[3 * i] = surface ? f[0] : 0.0f;
            truth.exr[3 * i + 1] = surface ? f[1] : 0.0f;
            truth.exr[3 * i + 2] = surface ? f[2] : std::numeric_limits<float>::infinity();
            if (surface)
                truth.visibility[i] = visibilityAt(width, height, x + 0.5 + f[0], y + 0.5 + f[1], f[2], targetDepth);
        }
    return truth;
}

std::vector<float> disparityChange(std::span<const float> flow, std::span<const float> depth, double focalBaseline) {
    require(flow.size() == 4 * depth.size(), "disparityChange: image sizes differ");
    std::vector<float> change(depth.size(), std::numeric_limits<float>::infinity());
    for (size_t i = 0; i < depth.size(); ++i)
        if (flow[4 * i + 3] != 0.0f && flow[4 * i + 2] > 0.0f && depth[i] > 0.0f && std::isfinite(depth[i]))
            change[i] = float(focalBaseline / double(flow[4 * i + 2]) - focalBaseline / double(depth[i]));
    return change;
}

} // namespace sward
