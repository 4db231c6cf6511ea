#include "scene/sensor_exposure.h"

#include "common/json_reader.h"
#include "scene/sensor_model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

double sensorReadout(const SensorParams& p, double light, uint32_t channel, double normal) {
    const SensorElectronics& x = p.electronics;
    const double epu = p.electronsPerUnit;
    const double black = x.blackLevel.value_or(0.0);
    if (!(epu > 0.0 && std::isfinite(light))) {
        double v = x.whiteBalance[channel] * (x.gain * light);
        if (x.blackLevel && std::isfinite(v)) v = std::max(v + black, 0.0);
        return v;
    }
    double electrons = light * epu;
    const double afterGain = x.readNoiseAfterGain / x.gain; // referred to the gain's input
    electrons += std::sqrt(std::max(electrons, 0.0) + p.readNoise * p.readNoise + afterGain * afterGain) * normal;
    if (p.fullWell > 0.0) electrons = std::min(electrons, p.fullWell);
    // G = 1 and white balance 1 multiply exactly: the value is the one the model gave before gain existed.
    double v = x.whiteBalance[channel] * (electrons / epu * x.gain);
    if (x.blackLevel) v = std::max(v + black, 0.0);
    if (p.fullWell > 0.0) v = std::min(v, black + p.fullWell / epu);
    return v;
}

void parseSensorElectronics(JsonReader& r, SensorParams& params) {
    SensorElectronics& x = params.electronics;
    if (r.has("gain") && (r.has("iso") || r.has("base_iso")))
        r.fail("'" + r.path() + "' must give either 'gain' or 'iso' (with 'base_iso'), not both");
    x.gain = r.number("gain", 1.0, 1e-3, 1e4);
    x.baseIso = r.number("base_iso", 100.0, 1.0, 1e7);
    x.iso = r.number("iso", 0.0, 1.0, 1e7);
    if (r.has("base_iso") && !r.has("iso")) r.fail(r.name("base_iso") + " needs 'iso'");
    if (x.iso > 0.0) {
        x.gain = x.iso / x.baseIso;
        if (!(x.gain >= 1e-3 && x.gain <= 1e4))
            r.fail(r.name("iso") + " / 'base_iso' must give a gain between 0.001 and 10000 (got " +
                   formatNumber(x.gain) + ")");
    }
    x.readNoiseAfterGain = r.number("read_noise_after_gain", 0.0, 0.0, 1e9);
    if (x.readNoiseAfterGain > 0.0 && params.electronsPerUnit <= 0.0)
        r.fail(r.name("electrons_per_unit") + " must be positive when 'read_noise_after_gain' is set");
    if (r.has("black_level")) x.blackLevel = r.number("black_level", 0.0, 0.0, 1e4);
    const glm::dvec3 wb = r.vector<3>("white_balance", glm::dvec3(1.0), 1e-3, 1e3);
    x.whiteBalance = {wb.x, wb.y, wb.z};
}

void sensorElectronicsToJson(const SensorElectronics& x, nlohmann::json& json) {
    if (x.iso > 0.0) {
        json["iso"] = x.iso;
        json["base_iso"] = x.baseIso;
    } else if (x.gain != 1.0) {
        json["gain"] = x.gain;
    }
    if (x.readNoiseAfterGain != 0.0) json["read_noise_after_gain"] = x.readNoiseAfterGain;
    if (x.blackLevel) json["black_level"] = *x.blackLevel;
    if (x.whiteBalance != std::array<double, 3>{1.0, 1.0, 1.0})
        json["white_balance"] = {x.whiteBalance[0], x.whiteBalance[1], x.whiteBalance[2]};
}

} // namespace sward
