#include "dataset/occlusion.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

bool hasTruth(float d) {
    return std::isfinite(d) && d > 0.0f;
}

// Whether the point of disparity `d` whose match in the other view's row is `match` is seen there.
bool seen(const float* otherRow, uint32_t width, double d, double match) {
    if (!(match >= -0.5 && match <= double(width) - 0.5)) return false; // out of the other view
    const double before = std::floor(match);
    auto nearer = [&](double centre) {
        const float other = otherRow[uint32_t(std::clamp(centre, 0.0, double(width - 1)))];
        return hasTruth(other) && double(other) > d + kOcclusionTolerance;
    };
    // A match on a centre is that centre's ray alone.
    return !(nearer(before) && (match == before || nearer(before + 1.0)));
}

} // namespace

std::vector<Visibility> visibilityInOtherView(uint32_t width, uint32_t height, std::span<const float> own,
                                              std::span<const float> other, int matchDirection) {
    const size_t pixels = size_t(width) * height;
    require(own.size() == pixels && other.size() == pixels, "visibilityInOtherView: disparity sizes differ");
    std::vector<Visibility> visibility(pixels, Visibility::NoTruth);
    for (uint32_t y = 0; y < height; ++y) {
        const float* ownRow = own.data() + size_t(y) * width;
        const float* otherRow = other.data() + size_t(y) * width;
        for (uint32_t x = 0; x < width; ++x) {
            if (!hasTruth(ownRow[x])) continue;
            const double d = ownRow[x], match = double(x) + matchDirection * d;
            visibility[size_t(y) * width + x] = seen(otherRow, width, d, match) ? Visibility::Visible
                                                                               : Visibility::Occluded;
        }
    }
    return visibility;
}

std::vector<uint8_t> occlusionMaskPixels(const std::vector<Visibility>& visibility) {
    std::vector<uint8_t> mask(visibility.size());
    for (size_t i = 0; i < visibility.size(); ++i)
        mask[i] = visibility[i] == Visibility::Visible ? 255 : visibility[i] == Visibility::Occluded ? 128 : 0;
    return mask;
}

} // namespace sward
