// The ground-truth images of a rendered frame as a dataset stores them (docs/dataset-format.md): the one
// conversion used by the dataset writer and by the Python module's frames, so both are bitwise the same.
#pragma once

#include "dataset/frame_images.h"

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

struct FrameTruth {
    std::vector<uint8_t> semantic;     // class per pixel (labels >> gpu::kInstanceBits)
    std::vector<float> instance;       // instance id per pixel, exact in float32 (ids < 2^24)
    std::vector<float> tile;           // worlds of several tiles: the plant's tile label per pixel (FrameImages::tiles)
    std::vector<float> disparity;      // stereo: f * B / depth in pixels, 0 where nothing was hit; empty for mono
    std::vector<float> rightDisparity; // the same of the right view's depth, when the frame has it
    // An unsynchronised rig (FrameImages::rightDepthAtLeftTime): the other view's disparity at each view's own time,
    // for the occlusion masks; empty for a synchronised rig (the views' own are).
    std::vector<float> rightDisparityAtLeftTime, disparityAtRightTime;
};

// The colour as the dataset stores it: alpha is coverage, and every pixel is covered by a surface or by the sky, so
// it is 1. (The renderer's resolved alpha is the mean of alpha-to-coverage and blend values, meaningless to a user.)
std::vector<uint16_t> colourWithCoverage(std::span<const uint16_t> rgbaHalf);

// `focalPx` and `baseline` (metres) are the left camera's and the rig's; baseline 0 = mono (no disparity).
FrameTruth frameTruth(const FrameImages& images, double focalPx, double baseline);

} // namespace sward
