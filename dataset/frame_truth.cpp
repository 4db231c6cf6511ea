#include "dataset/frame_truth.h"

#include "scene/camera_rig.h"
#include "shared/gpu_layout.h"

namespace sward {

FrameTruth frameTruth(const FrameImages& images, double focalPx, double baseline) {
    const size_t pixels = size_t(images.width) * images.height;
    FrameTruth truth{std::vector<uint8_t>(pixels), std::vector<float>(pixels), {}};
    for (size_t i = 0; i < pixels; ++i) {
        truth.semantic[i] = uint8_t(images.labels[i] >> gpu::kInstanceBits);
        truth.instance[i] = float(images.labels[i] & ((1u << gpu::kInstanceBits) - 1u)); // exact: ids < 2^24
    }
    if (baseline > 0.0) {
        truth.disparity.resize(pixels);
        for (size_t i = 0; i < pixels; ++i) truth.disparity[i] = disparityOf(focalPx, baseline, images.depth[i]);
    }
    return truth;
}

} // namespace sward
