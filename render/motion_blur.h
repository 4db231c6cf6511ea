// Exposure time and motion blur (camera.sensor.shutter_s and motion_samples; docs/scene-format.md).
//
// A camera integrates light over its exposure while it and the scene move. With a shutter, sward's colour image is
// the mean of N instantaneous colour renders at sub-frame times centred on the frame's time t,
//   t_i = t + shutter_s * ((i + 0.5) / N - 0.5),   i = 0 .. N-1,
// each with the rig, the objects on their paths and the wind at t_i, and the interaction state of the frame's own
// tick: the simulation steps once per frame (a fixed-step tick), the sub-frames never tick it again, so plants bent
// by a wheel stay as the frame's tick left them over the exposure. The mean is taken in float, in the order
// i = 0 .. N-1, and rounded to half once: bitwise repeatable on any machine. Ground truth (depth, disparity, labels,
// normals, flow, range sensors) stays the single instant t, the exposure's middle, rendered once by a truth-only
// render (no colour pass). The sensor model (vignetting, distortion, noise) applies after the mean: light is
// integrated first, then the sensor reads it out.
#pragma once

#include "scene/camera_rig.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sward {

class OffscreenFrame;
class SceneRenderer;
struct SceneResources;

// motion_samples "auto": one sub-frame per pixel of camera motion over the exposure, within these bounds.
inline constexpr uint32_t kMinAutoMotionSamples = 2;
inline constexpr uint32_t kMaxAutoMotionSamples = 32;

// The N sub-frame times of an exposure of `shutterSeconds` centred on `time` (samples >= 1).
std::vector<double> exposureTimes(double time, double shutterSeconds, uint32_t samples);

// The largest image displacement (pixels) between `start` and `end` of the points `start` sees through its image's
// corners, edge midpoints and centre, at infinity (the rotation) and at planar depth `nearDepth` (the translation's
// parallax of the nearest surface the rig expects: camera.min_depth). Infinite when a point leaves the half-space in
// front of `end`. Scene objects' own motion is not counted.
double cameraMotionPixels(const Camera& start, const Camera& end, double nearDepth);

// motion_samples "auto" for that displacement: ceil(pixels) within [kMinAutoMotionSamples, kMaxAutoMotionSamples].
uint32_t autoMotionSamples(double motionPixels);

// The motion_blur output: per pixel of `centre` (the frame's instant), the distance in pixels between where its
// surface point (at planar depth `depth`, +inf: the sky's direction) is seen by `start` and by `end` (the rig at the
// exposure's two ends), i.e. the blur length the camera's motion gives that pixel. The geometry is assumed static:
// the scene objects' and the plants' own motion is not in it. 0 where the point is behind either camera.
std::vector<float> motionBlurLengths(const Camera& start, const Camera& centre, const Camera& end,
                                     std::span<const float> depth);

// The sub-frame times of `frame` of the scene's sequence (empty when the sensor is off or has no shutter); "auto"
// measures the left camera's motion between the rigs at the exposure's two ends.
std::vector<double> frameExposureTimes(const SceneResources& r, const SensorParams& sensor, uint32_t width,
                                       uint32_t height, uint32_t frame);
// The same for an exposure centred on any `time` (an unsynchronised rig's right camera, render/sequence_frame.h);
// frameExposureTimes is this at frame * time_step.
std::vector<double> exposureTimesAt(const SceneResources& r, const SensorParams& sensor, uint32_t width,
                                    uint32_t height, double time);

// The running mean of colour images (half bit patterns): a float sum in the order added, divided once and rounded
// to half once.
class ExposureMean {
public:
    void add(std::span<const uint16_t> rgbaHalf);
    std::vector<uint16_t> meanHalf() const;

private:
    std::vector<float> sum_;
    uint32_t count_ = 0;
};

struct ExposureColour {
    std::vector<uint16_t> left, right; // right empty for a single camera
};

// The colour of an exposure: a colour-only render of the rig `rigAt(t_i)` at each of `times` (wind and objects at
// `timeOffset` + t_i), in order, `prologue` recorded before the first (the frame's tick), averaged by ExposureMean.
ExposureColour renderExposure(SceneRenderer& renderer, OffscreenFrame& target,
                              const std::function<RigCameras(double)>& rigAt, bool stereo,
                              std::span<const double> times, double timeOffset, uint32_t frameIndex,
                              const std::function<void(VkCommandBuffer)>& prologue);

} // namespace sward
