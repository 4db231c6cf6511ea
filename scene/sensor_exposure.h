// The sensor's electronics after the photo-electrons, and the ISP's linear steps: analog gain (ISO), read noise
// before and after the gain, full well and ADC clipping, black level and white balance (issue 48).
//
// Per pixel channel, after lens, exposure and vignetting have given the light s reaching the pixel (radiance units;
// scene/sensor_model.h), with G the analog gain, epu electrons_per_unit, n a standard normal:
//   e  = s * epu                                            expected photo-electrons
//   e' = e + sqrt(max(e, 0) + read_noise^2 + (read_noise_after_gain / G)^2) * n
//                                                           shot and read noise, referred to the gain's input
//   e' = min(e', full_well)                                 the well saturates (full_well > 0)
//   v  = G * e' / epu                                       amplified back to radiance units (signal and noise)
//   v  = white_balance[c] * v                               the ISP's per-channel digital gain on the raw signal
//   v  = v + black_level, then v = max(v, 0)                the ADC's pedestal and floor (only with black_level)
//   v  = min(v, black_level + full_well / epu)              the ADC's white level, matched to the well at G = 1
// So a higher gain at a shorter exposure gives the same mean with more noise (the electrons set the SNR), the ADC
// clips at full_well / G electrons, and a channel the white balance amplifies carries its noise amplified too.
// Without electrons_per_unit (no noise) the steps left are v = white_balance[c] * G * s (+ black level, floor).
// The defaults (G = 1, no read noise after the gain, white balance 1, no black level) give the image of the model
// before these keys existed, bit for bit: every step they add is then an exact multiplication by 1 or a no-op.
#pragma once

#include "common/exact_math.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace sward {

class JsonReader;
struct SensorParams;

// Auto-exposure (JSON "auto_exposure"): the exposure of frame k is 2^clamp(log2(target_grey) - S_k, min_ev, max_ev),
// S_k the metered luminance in stops, smoothed over the frames before it:
//   S_k = sum_{i=0..W'} r^i log2(M_{k-i}) / sum_{i=0..W'} r^i,   W' = min(W, k),   W = ceil(5 time_constant_s / dt),
//   r = (2 tau - dt) / (2 tau + dt)  (the (1,1) Pade form of exp(-dt / tau))
// with log2 and 2^x by + - * /, frexp and ldexp only (exactLog2, exactExp2): the same bits on every machine. M_j is
// the mean luminance (Rec. 709 weights) of frame j's ideal colour image (before lens and sensor), so the state has
// no feedback and frame k's exposure is a pure function of the ideal renders of frames k - W .. k: a shard or a
// resumed run re-meters the W frames before its first one and gets the very same value. The weights beyond W hold
// e^-5 = 0.7 % of the filter's mass; a step in the scene's light is followed by 63 % of its stops after one time
// constant (more at the sequence's start, where the window is normalised over fewer frames). time_constant_s 0:
// every frame metered alone.
// The scene key camera.sensor.auto_exposure; a run's state (the meters, the priming of a shard's or a resumed run's
// first window, the record per frame in auto_exposure/) is render/auto_exposure.h.
struct AutoExposureParams {
    bool enabled = false;
    double targetGrey = 0.18;           // the exposed mean luminance aimed at
    double timeConstantSeconds = 0.5;   // tau
    double minEv = -16.0, maxEv = 16.0; // limits of the exposure factor, in stops
    // The most frames before a frame its exposure depends on (JSON "max_window_frames"); 0: ceil(5 tau / dt). A
    // smaller bound cuts the filter's tail (a step is then followed a little faster, and wholly after that many
    // frames) and what a shard or a resumed run renders first.
    uint32_t maxWindowFrames = 0;
};

inline constexpr double kAutoExposureSpan = 5.0;           // the window in time constants
inline constexpr double kAutoExposureFloorEv = -40.0;      // the meter of a black view, in stops
inline constexpr uint32_t kMaxAutoExposureWindow = 100000; // the largest max_window_frames

struct SensorElectronics {
    double gain = 1.0;                // analog gain G (JSON "gain", "gain_db" or "iso" / "base_iso")
    std::optional<double> gainDb;     // the gain in dB the scene gave (written back as given)
    double iso = 0.0;                 // the ISO the scene gave (0: none; then "gain" is written back)
    double baseIso = 100.0;           // the ISO at which G = 1
    double readNoiseAfterGain = 0.0;  // read noise added after the gain, electrons as counted at G = 1
    std::optional<double> blackLevel; // pedestal in radiance units; present = the output is floored at 0
    std::array<double, 3> whiteBalance{1.0, 1.0, 1.0}; // per-channel digital gains (R, G, B)

    bool isDefault() const {
        return gain == 1.0 && !gainDb && iso == 0.0 && baseIso == 100.0 && readNoiseAfterGain == 0.0 && !blackLevel &&
               whiteBalance == std::array<double, 3>{1.0, 1.0, 1.0};
    }
};

// Frames before frame k that its exposure depends on (W above, at most maxWindowFrames when set); 0 without smoothing.
uint32_t autoExposureWindow(const AutoExposureParams& params, double timeStep);
// M: the mean Rec. 709 luminance of the finite pixels of a linear half RGBA image, summed in pixel order (0 if none).
double meterLuminance(std::span<const uint16_t> rgbaHalf);
// The exposure factor of frame k from `meters`: the meters of frames k - n + 1 .. k in order (n = min(W, k) + 1;
// more are ignored from the front). Precondition: meters not empty.
double autoExposureFactor(const AutoExposureParams& params, double timeStep, std::span<const double> meters);
// Reads the "auto_exposure" object of a sensor (errors name 'camera.sensor.auto_exposure.<key>').
AutoExposureParams parseAutoExposure(JsonReader& sensor);
nlohmann::json autoExposureToJson(const AutoExposureParams& params);

// The output value of one colour channel `channel` (0..2) from the light `light` reaching the pixel (exposure and
// vignetting applied), `normal` the pixel channel's standard normal (used only with electrons_per_unit > 0).
// Non-finite light gets the gains and black level but no noise and no clipping. Pure: same inputs, same bits.
double sensorReadout(const SensorParams& params, double light, uint32_t channel, double normal);

// Reads "gain" | "gain_db" | ("iso", "base_iso"), "read_noise_after_gain", "black_level", "white_balance" from the sensor
// object into `params.electronics` (errors name the key: "scene.json: 'camera.sensor.iso' must be ...").
// Call before JsonReader::finish(), after electrons_per_unit has been read.
void parseSensorElectronics(JsonReader& reader, SensorParams& params);
// Adds the keys that differ from the defaults to `json` (a sensor without them is written as before).
void sensorElectronicsToJson(const SensorElectronics& electronics, nlohmann::json& json);

} // namespace sward
