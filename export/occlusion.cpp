#include "export/occlusion.h"

#include "common/error.h"
#include "io/disparity_files.h"

#include <cmath>

namespace sward {

std::vector<Visibility> leftVisibility(uint32_t width, uint32_t height, std::span<const float> disparity) {
    require(disparity.size() == size_t(width) * height, "leftVisibility: disparity size does not match the image");
    std::vector<Visibility> visibility(disparity.size(), Visibility::NoTruth);
    std::vector<float> nearest(width);
    for (uint32_t y = 0; y < height; ++y) {
        const float* row = disparity.data() + size_t(y) * width;
        // The right column a left pixel lands on: x - d, rounded to the nearest centre; -1 when outside.
        auto column = [&](uint32_t x) {
            const double c = std::floor(double(x) - double(row[x]) + 0.5);
            return c >= 0.0 && c < double(width) ? int64_t(c) : int64_t(-1);
        };
        std::fill(nearest.begin(), nearest.end(), 0.0f);
        for (uint32_t x = 0; x < width; ++x)
            if (isValidDisparity(row[x]))
                if (const int64_t c = column(x); c >= 0) nearest[c] = std::max(nearest[c], row[x]);
        for (uint32_t x = 0; x < width; ++x) {
            if (!isValidDisparity(row[x])) continue;
            const int64_t c = column(x);
            const bool hidden = c < 0 || nearest[c] > row[x] + kOcclusionTolerance;
            visibility[size_t(y) * width + x] = hidden ? Visibility::Occluded : Visibility::Visible;
        }
    }
    return visibility;
}

} // namespace sward
