#include "render/auto_exposure.h"

#include "common/error.h"

#include <algorithm>

namespace sward {

AutoExposure::AutoExposure(const AutoExposureParams& params, double timeStep)
    : params_(params), timeStep_(timeStep), window_(autoExposureWindow(params, timeStep)) {
    require(params.enabled && timeStep > 0.0, "AutoExposure: needs auto_exposure enabled and a positive time step");
}

std::vector<uint32_t> AutoExposure::framesToRender(const std::vector<uint32_t>& todo) const {
    std::vector<uint32_t> frames;
    for (const uint32_t frame : todo) {
        require(frames.empty() || frame > frames.back(), "AutoExposure::framesToRender: frames out of order");
        // From the window's first frame, or from the frame after the last one already listed (windows overlap).
        uint32_t first = frame > window_ ? frame - window_ : 0;
        if (!frames.empty()) first = std::max(first, frames.back() + 1);
        for (uint32_t f = first; f <= frame; ++f) frames.push_back(f);
    }
    return frames;
}

FrameImages::Exposure AutoExposure::meter(uint32_t frame, std::span<const uint16_t> rgbaHalf) {
    const double value = meterLuminance(rgbaHalf);
    meters_[frame] = value;
    while (!meters_.empty() && meters_.begin()->first + window_ < frame) meters_.erase(meters_.begin());
    // The meters of frame - n + 1 .. frame, oldest first, as far back as they are recorded without a gap.
    std::vector<double> window{value};
    for (uint32_t back = 1; back <= std::min(window_, frame); ++back) {
        const auto it = meters_.find(frame - back);
        if (it == meters_.end()) break;
        window.push_back(it->second);
    }
    std::reverse(window.begin(), window.end());
    return {.meter = value, .factor = autoExposureFactor(params_, timeStep_, window)};
}

} // namespace sward
