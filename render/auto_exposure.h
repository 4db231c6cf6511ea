// Auto-exposure's state in a run (camera.sensor.auto_exposure; the law is scene/sensor_exposure.h): the meters of the
// frames rendered so far, from which each frame's exposure factor follows.
//
// The meter of frame k is the mean luminance of its left colour as the lens receives it: after the exposure's
// sub-frames (motion blur) and a rolling shutter's bands, before the lens (depth of field, MTF) and the sensor model.
// The lens only moves light between pixels (its mean is the same but for the image's border), and metering before it
// keeps the meter a function of the render alone, the same with or without a lens. Both views of a stereo rig get
// the left camera's factor: one exposure control for a synchronised pair, as machine-vision stereo heads do.
//
// Frame k's factor depends on the meters of frames k - W .. k only (W = autoExposureWindow), never on the exposure
// applied before (no feedback), so a run that starts at frame f (a shard, a resumed run) renders frames f - W .. f - 1
// for their meter alone (nothing written) and then writes bitwise the frames a whole run writes. That costs W renders
// per run start (framesToRender); a sequential run meters each frame as it renders it.
#pragma once

#include "dataset/frame_images.h"
#include "scene/sensor_exposure.h"

#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace sward {

class AutoExposure {
public:
    AutoExposure(const AutoExposureParams& params, double timeStep);

    // W: the frames before a frame that its exposure depends on.
    uint32_t window() const { return window_; }
    // The frames a run must render, in order, to write `todo` (increasing): each frame of todo and the W frames before
    // it (the frames in between the windows only where they are within one).
    std::vector<uint32_t> framesToRender(const std::vector<uint32_t>& todo) const;
    // Meters frame `frame` from its left colour (linear half RGBA, before lens and sensor) and returns its exposure:
    // the factor from the meters of the frames frame - W .. frame that are recorded without a gap before it (all of
    // them when the frames came from framesToRender; a Session after restore_state has fewer). Meters older than the
    // window are dropped.
    FrameImages::Exposure meter(uint32_t frame, std::span<const uint16_t> rgbaHalf);
    // Forgets every meter (the window restarts as at a sequence's start).
    void clear() { meters_.clear(); }

private:
    AutoExposureParams params_;
    double timeStep_;
    uint32_t window_;
    std::map<uint32_t, double> meters_; // frame -> its meter, the last W + 1 frames metered at most
};

} // namespace sward
