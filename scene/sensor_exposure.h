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

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <optional>

namespace sward {

class JsonReader;
struct SensorParams;

struct SensorElectronics {
    double gain = 1.0;                // analog gain G (JSON "gain", or "iso" / "base_iso")
    double iso = 0.0;                 // the ISO the scene gave (0: none; then "gain" is written back)
    double baseIso = 100.0;           // the ISO at which G = 1
    double readNoiseAfterGain = 0.0;  // read noise added after the gain, electrons as counted at G = 1
    std::optional<double> blackLevel; // pedestal in radiance units; present = the output is floored at 0
    std::array<double, 3> whiteBalance{1.0, 1.0, 1.0}; // per-channel digital gains (R, G, B)

    bool isDefault() const {
        return gain == 1.0 && iso == 0.0 && baseIso == 100.0 && readNoiseAfterGain == 0.0 && !blackLevel &&
               whiteBalance == std::array<double, 3>{1.0, 1.0, 1.0};
    }
};

// The output value of one colour channel `channel` (0..2) from the light `light` reaching the pixel (exposure and
// vignetting applied), `normal` the pixel channel's standard normal (used only with electrons_per_unit > 0).
// Non-finite light gets the gains and black level but no noise and no clipping. Pure: same inputs, same bits.
double sensorReadout(const SensorParams& params, double light, uint32_t channel, double normal);

// Reads "gain" | ("iso", "base_iso"), "read_noise_after_gain", "black_level", "white_balance" from the sensor
// object into `params.electronics` (errors name the key: "scene.json: 'camera.sensor.iso' must be ...").
// Call before JsonReader::finish(), after electrons_per_unit has been read.
void parseSensorElectronics(JsonReader& reader, SensorParams& params);
// Adds the keys that differ from the defaults to `json` (a sensor without them is written as before).
void sensorElectronicsToJson(const SensorElectronics& electronics, nlohmann::json& json);

} // namespace sward
