// Camera sensor simulation for rendered colour: lens distortion, vignetting, exposure, photon and read noise.
//
// Applied to the HDR colour image only; depth, disparity and masks stay in the ideal pinhole model, so ground
// truth is exact and a user who wants it in the distorted image can apply the same (OpenCV) lens model.
// The rendered image is the ideal pinhole view. Output pixel (u, v) of the simulated image shows the ideal
// point p with distort(p) = (u, v), Brown-Conrady in OpenCV's convention and parameter order (k1, k2, p1, p2,
// k3) on normalised coordinates x = (u - cx) / fx, y = (v - cy) / fy:
//   r2 = x^2 + y^2,  radial = 1 + k1 r2 + k2 r2^2 + k3 r2^3
//   x_d = x radial + 2 p1 x y + p2 (r2 + 2 x^2),   y_d = y radial + p1 (r2 + 2 y^2) + 2 p2 x y
// Pixel coordinates follow camera.h: the centre of pixel (i, j) is (i + 0.5, j + 0.5).
//
// The lens's blur (depth of field, MTF, chromatic aberration: scene/sensor_optics.h) runs before all of this.
// Per pixel and colour channel, in this order (physically: lens, then sensor):
//   s = exposure * vignette(p) * ideal(p)           linear radiance reaching the pixel (bilinear in the ideal image)
//   e = s * electrons_per_unit                       expected photo-electrons
//   e' = e + sqrt(max(e, 0) + read_noise^2) * n      Poisson shot noise as a Gaussian with variance e, plus read noise
//   e' = min(e', full_well)                          when full_well > 0
//   out = e' / electrons_per_unit                    back to the image's linear units
//   then gain, white balance, black level and the ADC's clip: scene/sensor_exposure.h (sensorReadout)
// With a Bayer pattern (camera.sensor.bayer) only each pixel's photosite channel is read out, with its own noise, and
// the ISP then demosaics the other two (scene/sensor_bayer.h); without one every channel is, as above.
// n is a standard normal from Box-Muller on two uniforms hashed from (seed, frame, camera, pixel, channel), so
// the result is a pure function of its inputs: bitwise repeatable, any order, any thread count. Noise is
// zero-mean (no clamping at 0), so averages over many frames converge to the noise-free image. Alpha is
// resampled with the colour (it is coverage, which the lens moves) but gets no exposure, vignetting or noise.
#pragma once

#include "scene/sensor_bayer.h"
#include "scene/sensor_exposure.h"
#include "scene/sensor_optics.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

struct Camera;

struct SensorParams {
    bool enabled = false;    // off by default: the colour image is the ideal render, bit for bit
    double exposure = 1.0;   // linear scale on radiance (JSON: "exposure", or "exposure_ev" = log2 of it)
    double vignetting = 0.0; // 0..1: gain = 1 - v + v cos^4(theta), theta the ray's angle to the optical axis
    double k1 = 0.0, k2 = 0.0, k3 = 0.0; // radial distortion (OpenCV)
    double p1 = 0.0, p2 = 0.0;           // tangential distortion (OpenCV)
    double electronsPerUnit = 0.0;       // photo-electrons per unit linear radiance; 0 = no noise at all
    double readNoise = 0.0;              // read noise standard deviation, electrons
    double fullWell = 0.0;               // saturation in electrons; 0 = none (HDR output)
    // Exposure and motion blur (render/motion_blur.h): the colour image is the mean over the exposure.
    double shutterSeconds = 0.0; // exposure time; 0 = an instantaneous image (no sub-frames)
    uint32_t motionSamples = 0;  // sub-frames per exposure, 2..kMaxMotionSamples; 0 = "auto" (from the motion)
    // Rolling shutter (render/rolling_shutter.h): row r read at t + readout_s ((r + 0.5) / H - 0.5).
    double readoutSeconds = 0.0; // 0 = a global shutter (every row at the frame's time)
    uint32_t readoutBands = 0;   // renders per frame, each a band of rows at one time; 0 (or > H) = every row
    // An unsynchronised stereo rig (render/sequence_frame.h): the right camera's exposure and readout start this much
    // later than the left's (negative: earlier); 0 = a synchronised rig. Needs a stereo rig (scene/scene.cpp checks).
    double stereoOffsetSeconds = 0.0;
    SensorElectronics electronics;   // gain, black level, white balance (scene/sensor_exposure.h)
    AutoExposureParams autoExposure; // the exposure from the frames' meters (render/auto_exposure.h)
    LensOptics optics;     // depth of field, MTF blur, chromatic aberration (scene/sensor_optics.h), before all else
    uint32_t bitDepth = 0; // the digital output raw/ (scene/sensor_raw.h): 8..16 bits; 0 = none
    ColourFilterArray cfa; // a Bayer mosaic and its demosaicing (scene/sensor_bayer.h); none = three channels

    bool hasDistortion() const { return k1 != 0.0 || k2 != 0.0 || k3 != 0.0 || p1 != 0.0 || p2 != 0.0; }
};

inline constexpr double kMaxShutterSeconds = 1.0;
inline constexpr uint32_t kMaxMotionSamples = 64;
inline constexpr double kMaxReadoutSeconds = 1.0;
inline constexpr uint32_t kMaxReadoutBands = 16384;
inline constexpr double kMaxStereoOffsetSeconds = 1.0; // |stereo_offset_s|

// Pinhole intrinsics in pixels (camera.h convention).
struct Intrinsics {
    double fx = 1.0, fy = 1.0, cx = 0.5, cy = 0.5;
    uint32_t width = 1, height = 1;
    static Intrinsics of(const Camera& camera);
};

// OpenCV's forward model on normalised coordinates: the distorted normalised point of ideal point (x, y).
void distortNormalized(const SensorParams& params, double x, double y, double& xd, double& yd);
// Inverse of distortNormalized by Newton iteration: the ideal (x, y) with distort(x, y) = (xd, yd).
void undistortNormalized(const SensorParams& params, double xd, double yd, double& x, double& y);

// The per-camera part that does not change between frames (the resampling map and vignetting gains), built
// once per rig and applied to every frame.
class SensorModel {
public:
    SensorModel(const SensorParams& params, const Intrinsics& intrinsics);

    // `rgba`: width*height*4 linear floats, top row first; replaced by the simulated image.
    // `exposureScale`: auto-exposure's factor of the frame (render/auto_exposure.h), on top of `exposure`; 1 multiplies
    // nothing (the image of before, bit for bit).
    void apply(uint64_t seed, uint32_t frame, uint32_t camera, std::span<float> rgba, double exposureScale = 1.0) const;
    // Same on half bit patterns (as FrameImages::rgbaHalf holds them); results rounded to nearest even.
    // `digital`: with a bit depth, set to the DN of the float output before it is rounded to half (sensor_raw.h).
    void applyHalf(uint64_t seed, uint32_t frame, uint32_t camera, std::span<uint16_t> rgbaHalf,
                   double exposureScale = 1.0, std::vector<uint16_t>* digital = nullptr) const;

    const SensorParams& params() const { return params_; }

private:
    SensorParams params_;
    Intrinsics intrinsics_;
    std::vector<float> sourceUv_; // per output pixel: where to sample the ideal image (pixel units); empty = identity
    std::vector<float> gain_;     // per output pixel: exposure * vignetting
};

// One-shot convenience (builds the map every call; prefer SensorModel for sequences).
void applySensor(const SensorParams& params, const Intrinsics& intrinsics, uint64_t seed, uint32_t frame,
                 uint32_t camera, std::span<float> rgba);
void applySensorHalf(const SensorParams& params, const Intrinsics& intrinsics, uint64_t seed, uint32_t frame,
                     uint32_t camera, std::span<uint16_t> rgbaHalf);

// Reads a sensor object: {"enabled", "exposure" | "exposure_ev", "vignetting", "k1", "k2", "k3", "p1", "p2",
// "electrons_per_unit", "read_noise", "full_well", "shutter_s", "motion_samples"}, all optional. A present object
// without "enabled" is enabled. Errors name `source` and the JSON path, e.g.
// "scene.json: 'camera.sensor.k1' must be a number".
// A null `json` gives the defaults (disabled).
SensorParams parseSensor(const nlohmann::json& json, const std::string& source, const std::string& jsonPath);
// The parameters as JSON (the parser's keys), for frames.jsonl / manifests.
nlohmann::json sensorToJson(const SensorParams& params);

} // namespace sward
