// Which pixels of the left view have their match hidden in the right view, from the left ground-truth disparity
// alone: every left pixel is forward-warped to its right-image column (x - d, rounded to the nearest pixel
// centre) and the nearest surface (largest disparity) arriving at each right column wins. A left pixel is
// occluded when a surface nearer by more than kOcclusionTolerance pixels of disparity lands on its column, or
// when its match falls outside the right image. Surfaces the left view does not see at all cannot occlude here,
// so thin structures seen only by the right camera are missed (the exact mask needs the right view's own truth
// pass: docs/dataset-format.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

inline constexpr float kOcclusionTolerance = 1.0f; // pixels of disparity: neighbours on one slanted surface differ less

enum class Visibility : uint8_t { NoTruth = 0, Occluded = 1, Visible = 2 };

// Per pixel of a `width` x `height` left disparity map (0 = no truth, e.g. sky), top row first.
std::vector<Visibility> leftVisibility(uint32_t width, uint32_t height, std::span<const float> disparity);

} // namespace sward
