// Occlusion from the ground truth of both views of a rectified rig: is the surface a pixel sees also seen by the
// other camera? Left pixel x with disparity d shows its point at right x - d; right pixel x at left x + d. The
// other view's truth is a depth test there: the point is hidden when the other view's two pixel centres around
// the match (one centre when the match is on it; the edge centre twice at the image's edge) all see a surface nearer by more than
// kOcclusionTolerance pixels of disparity, and out of view when the match falls outside the other image
// ([-0.5, width - 0.5]). Two centres, not one: a ray between them may pass beside a thin blade that covers
// only one. The tolerance covers neighbouring blades and slanted surfaces at almost the same depth; it is not
// an exactness test (on one planar surface the other view's disparity interpolated at the match equals d to
// float rounding, but two neighbouring pixels often see two different blades).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

inline constexpr double kOcclusionTolerance = 0.5; // pixels of disparity

enum class Visibility : uint8_t { NoTruth = 0, Occluded = 1, Visible = 2 };

// Per pixel of the view whose disparity is `own` (top row first, 0 = no truth): `other` is the other view's.
// `matchDirection` is -1 for the left view (match at x - d), +1 for the right view (x + d).
std::vector<Visibility> visibilityInOtherView(uint32_t width, uint32_t height, std::span<const float> own,
                                              std::span<const float> other, int matchDirection);

// occlusion/NNNNNN.png values, Middlebury's mask0nocc convention: 255 visible in both views, 128 occluded,
// 0 no truth (sky).
std::vector<uint8_t> occlusionMaskPixels(const std::vector<Visibility>& visibility);

} // namespace sward
