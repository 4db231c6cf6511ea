// Motion ground truth files (render.flow, docs/dataset-format.md): a truth pass's flow attachment (FrameImages::
// flowForward ...; x, y the pixel offset to where the pixel's surface point is at the target tick, z that point's
// planar depth in the target tick's camera, w 1 where the pixel shows a surface) turned into the files' fields, and
// the point's visibility in the target frame, from that frame's own truth.
#pragma once

#include "dataset/occlusion.h"
#include "io/flow_files.h"

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

// A point is hidden in the target frame when the target's pixel centres around where it lands (one to four: the
// centres of the pixel square it falls in, clamped to the image) all see a surface nearer than its own depth there by
// more than this fraction; out of view when it lands outside the image or behind the camera. A tolerance, not an
// exactness test: neighbouring blades lie at almost the same depth.
inline constexpr double kFlowOcclusionTolerance = 0.02;

struct FlowTruth {
    FlowField flow;                     // (u, v); NaN where the pixel shows sky
    std::vector<float> exr;             // width*height*3: u, v, the point's depth at the target (0, 0, +inf: sky)
    std::vector<Visibility> visibility; // of each pixel's point in the target frame
};

// `flow`: width*height*4 floats of one view and direction; `targetDepth`: the target frame's planar depth of the same
// view (+inf sky).
FlowTruth flowTruth(uint32_t width, uint32_t height, std::span<const float> flow, std::span<const float> targetDepth);

// The SceneFlow datasets' disparity change: the point's disparity at the target tick minus its disparity now,
// f*B/z_target - f*B/z (`focalBaseline` = f*B, pixel metres); +inf where the pixel shows sky.
std::vector<float> disparityChange(std::span<const float> flow, std::span<const float> depth, double focalBaseline);

} // namespace sward
