#include "dataset/frame_truth.h"

#include "common/half_float.h"
#include "scene/camera_rig.h"
#include "shared/gpu_layout.h"

namespace sward {

std::vector<uint16_t> colourWithCoverage(std::span<const uint16_t> rgbaHalf) {
    std::vector<uint16_t> rgba(rgbaHalf.begin(), rgbaHalf.end());
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = floatToHalfBits(1.0f);
    return rgba;
}

FrameTruth frameTruth(const FrameImages& images, double focalPx, double baseline) {
    const size_t pixels = size_t(images.width) * images.height;
    FrameTruth truth{std::vector<uint8_t>(pixels), std::vector<float>(pixels), {}};
    for (size_t i = 0; i < pixels; ++i) {
        truth.semantic[i] = uint8_t(images.labels[i] >> gpu::kInstanceBits);
        truth.instance[i] = float(images.labels[i] & ((1u << gpu::kInstanceBits) - 1u)); // exact: ids < 2^24
    }
    truth.tile.assign(images.tiles.begin(), images.tiles.end()); // exact: labels < 2^16
    // The rig is rectified: both views share fx, and the right view's depth gives its own disparity.
    auto disparityOfDepth = [&](const std::vector<float>& depth) {
        std::vector<float> disparity(depth.size());
        for (size_t i = 0; i < depth.size(); ++i) disparity[i] = disparityOf(focalPx, baseline, depth[i]);
        return disparity;
    };
    if (baseline > 0.0) {
        truth.disparity = disparityOfDepth(images.depth);
        truth.rightDisparity = disparityOfDepth(images.rightDepth);
        if (!images.rightDepthAtLeftTime.empty()) {
            truth.rightDisparityAtLeftTime = disparityOfDepth(images.rightDepthAtLeftTime);
            truth.disparityAtRightTime = disparityOfDepth(images.leftDepthAtRightTime);
        }
    }
    return truth;
}

} // namespace sward
