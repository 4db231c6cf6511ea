#include "render/motion_blur.h"

#include "common/error.h"
#include "common/half_float.h"
#include "render/scene_renderer.h"
#include "render/sequence_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sward {

std::vector<double> exposureTimes(double time, double shutterSeconds, uint32_t samples) {
    require(samples >= 1, "an exposure has at least one sample");
    std::vector<double> times(samples);
    for (uint32_t i = 0; i < samples; ++i)
        times[i] = time + shutterSeconds * ((double(i) + 0.5) / double(samples) - 0.5);
    return times;
}

double cameraMotionPixels(const Camera& start, const Camera& end, double nearDepth) {
    const glm::dmat3 endFromWorld = glm::transpose(end.worldFromCamera); // a rotation: its inverse
    double largest = 0.0;
    for (double fu : {0.0, 0.5, 1.0})
        for (double fv : {0.0, 0.5, 1.0}) {
            const glm::dvec2 pixel(fu * start.width, fv * start.height);
            const glm::dvec3 ray = start.ray(pixel.x, pixel.y);
            const glm::dvec3 far = endFromWorld * ray; // a direction: only the rotation moves it
            const glm::dvec3 near = end.project(start.position + nearDepth * ray);
            if (far.z <= 0.0 || near.z <= 0.0) return std::numeric_limits<double>::infinity();
            const glm::dvec2 farPixel(end.fx * far.x / far.z + end.cx, end.fy * far.y / far.z + end.cy);
            largest = std::max({largest, glm::length(farPixel - pixel), glm::length(glm::dvec2(near) - pixel)});
        }
    return largest;
}

std::vector<float> motionBlurLengths(const Camera& start, const Camera& centre, const Camera& end,
                                     std::span<const float> depth) {
    require(depth.size() == size_t(centre.width) * centre.height, "motionBlurLengths: depth and camera sizes differ");
    // Where a camera sees a point (w = 1) or a direction (w = 0): pixel coordinates, nothing behind it.
    auto seen = [](const Camera& camera, const glm::dvec3& p, double w, glm::dvec2& pixel) {
        const glm::dvec3 c = glm::transpose(camera.worldFromCamera) * (p - w * camera.position);
        if (c.z <= 0.0) return false;
        pixel = {camera.fx * c.x / c.z + camera.cx, camera.fy * c.y / c.z + camera.cy};
        return true;
    };
    std::vector<float> lengths(depth.size(), 0.0f);
    for (uint32_t y = 0; y < centre.height; ++y)
        for (uint32_t x = 0; x < centre.width; ++x) {
            const size_t i = size_t(y) * centre.width + x;
            const glm::dvec3 ray = centre.ray(x + 0.5, y + 0.5);
            const bool sky = !(depth[i] < std::numeric_limits<float>::max());
            const glm::dvec3 p = sky ? ray : centre.position + double(depth[i]) * ray;
            glm::dvec2 a, b;
            if (seen(start, p, sky ? 0.0 : 1.0, a) && seen(end, p, sky ? 0.0 : 1.0, b))
                lengths[i] = float(glm::length(b - a));
        }
    return lengths;
}

uint32_t autoMotionSamples(double motionPixels) {
    if (!(motionPixels < double(kMaxAutoMotionSamples))) return kMaxAutoMotionSamples; // also NaN and infinity
    return std::max(kMinAutoMotionSamples, uint32_t(std::ceil(motionPixels)));
}

std::vector<double> frameExposureTimes(const SceneResources& r, const SensorParams& sensor, uint32_t width,
                                       uint32_t height, uint32_t frame) {
    return exposureTimesAt(r, sensor, width, height, double(frame) * r.scene.sequence.timeStep);
}

std::vector<double> exposureTimesAt(const SceneResources& r, const SensorParams& sensor, uint32_t width,
                                    uint32_t height, double time) {
    if (!sensor.enabled || sensor.shutterSeconds <= 0.0) return {};
    const double half = 0.5 * sensor.shutterSeconds;
    uint32_t samples = sensor.motionSamples;
    if (samples == 0) {
        const RigCameras start = sequenceRigAt(r, width, height, time - half);
        const RigCameras end = sequenceRigAt(r, width, height, time + half);
        samples = autoMotionSamples(cameraMotionPixels(start.left, end.left, r.scene.camera.rig.minDepth));
    }
    return exposureTimes(time, sensor.shutterSeconds, samples);
}

void ExposureMean::add(std::span<const uint16_t> rgbaHalf) {
    if (count_ == 0) sum_.assign(rgbaHalf.size(), 0.0f);
    require(rgbaHalf.size() == sum_.size(), "ExposureMean: the images' sizes differ");
    for (size_t k = 0; k < sum_.size(); ++k) sum_[k] += halfBitsToFloat(rgbaHalf[k]);
    ++count_;
}

std::vector<uint16_t> ExposureMean::meanHalf() const {
    std::vector<uint16_t> mean(sum_.size());
    const float count = float(count_);
    for (size_t k = 0; k < sum_.size(); ++k) mean[k] = floatToHalfBits(sum_[k] / count);
    return mean;
}

ExposureColour renderExposure(SceneRenderer& renderer, OffscreenFrame& target,
                              const std::function<RigCameras(double)>& rigAt, bool stereo,
                              std::span<const double> times, double timeOffset, uint32_t frameIndex,
                              const std::function<void(VkCommandBuffer)>& prologue) {
    require(!times.empty(), "an exposure has at least one sample");
    ExposureMean left, right;
    std::vector<uint16_t> leftImage, rightImage;
    for (size_t i = 0; i < times.size(); ++i) {
        // Each sub-frame is its own submission (renderColour waits): the objects' and constants' host-written slots
        // of frameIndex are rewritten for every sub-frame.
        const RigCameras rig = rigAt(times[i]);
        target.renderColour(renderer, rig.left, timeOffset + times[i], frameIndex,
                            i == 0 ? prologue : std::function<void(VkCommandBuffer)>(), stereo ? &rig.right : nullptr,
                            leftImage, &rightImage);
        left.add(leftImage);
        if (stereo) right.add(rightImage);
    }
    return {left.meanHalf(), stereo ? right.meanHalf() : std::vector<uint16_t>()};
}

} // namespace sward
