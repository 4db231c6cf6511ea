#include "scene/sensor_exposure.h"

#include "common/error.h"
#include "common/half_float.h"
#include "common/json_reader.h"
#include "scene/sensor_model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

constexpr double kLog2TenOver20 = 0.16609640474436811739; // log2(10) / 20: gain_db in stops

} // namespace

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

uint32_t autoExposureWindow(const AutoExposureParams& p, double timeStep) {
    if (!(p.timeConstantSeconds > 0.0)) return 0;
    const double frames = std::ceil(kAutoExposureSpan * p.timeConstantSeconds / timeStep);
    const double bound = p.maxWindowFrames > 0 ? double(p.maxWindowFrames) : double(UINT32_MAX);
    return uint32_t(std::min(frames, bound));
}

double meterLuminance(std::span<const uint16_t> rgbaHalf) {
    double sum = 0.0;
    uint64_t count = 0;
    for (size_t p = 0; p + 3 < rgbaHalf.size(); p += 4) {
        const double y = 0.2126 * halfBitsToFloat(rgbaHalf[p]) + 0.7152 * halfBitsToFloat(rgbaHalf[p + 1]) +
                         0.0722 * halfBitsToFloat(rgbaHalf[p + 2]);
        if (!std::isfinite(y)) continue;
        sum += y;
        ++count;
    }
    return count ? sum / double(count) : 0.0;
}

double autoExposureFactor(const AutoExposureParams& p, double timeStep, std::span<const double> meters) {
    require(!meters.empty(), "autoExposureFactor: no meter");
    const size_t n = std::min<size_t>(meters.size(), size_t(autoExposureWindow(p, timeStep)) + 1);
    const double tau = p.timeConstantSeconds;
    const double r = tau > 0.0 ? std::max((2.0 * tau - timeStep) / (2.0 * tau + timeStep), 0.0) : 0.0;
    // Smoothed in stops, so a step darker and one brighter are followed at the same pace; a black view counts as
    // kAutoExposureFloorEv.
    double weighted = 0.0, weights = 0.0, w = 1.0;
    for (size_t i = 0; i < n; ++i) { // newest first
        const double m = meters[meters.size() - 1 - i];
        weighted +=
            w * (m > 0.0 && std::isfinite(m) ? std::max(exactLog2(m), kAutoExposureFloorEv) : kAutoExposureFloorEv);
        weights += w;
        w *= r;
    }
    const double ev = exactLog2(p.targetGrey) - weighted / weights;
    return exactExp2(std::clamp(ev, p.minEv, p.maxEv));
}

AutoExposureParams parseAutoExposure(JsonReader& sensor) {
    AutoExposureParams p;
    if (!sensor.has("auto_exposure")) return p;
    JsonReader r = sensor.child("auto_exposure");
    p.enabled = r.boolean("enabled", true);
    p.targetGrey = r.number("target_grey", 0.18, 1e-4, 100.0);
    p.timeConstantSeconds = r.number("time_constant_s", 0.5, 0.0, 60.0);
    p.minEv = r.number("min_ev", -16.0, -30.0, 30.0);
    p.maxEv = r.number("max_ev", 16.0, -30.0, 30.0);
    if (p.minEv > p.maxEv) r.fail(r.name("min_ev") + " must not be above 'max_ev'");
    p.maxWindowFrames = uint32_t(r.integer("max_window_frames", 0, 1, kMaxAutoExposureWindow));
    r.finish();
    return p;
}

nlohmann::json autoExposureToJson(const AutoExposureParams& p) {
    nlohmann::json json = {{"enabled", p.enabled},
                           {"target_grey", p.targetGrey},
                           {"time_constant_s", p.timeConstantSeconds},
                           {"min_ev", p.minEv},
                           {"max_ev", p.maxEv}};
    if (p.maxWindowFrames > 0) json["max_window_frames"] = p.maxWindowFrames; // absent: the window of 5 tau
    return json;
}

void parseSensorElectronics(JsonReader& r, SensorParams& params) {
    SensorElectronics& x = params.electronics;
    if (int(r.has("gain")) + int(r.has("gain_db")) + int(r.has("iso") || r.has("base_iso")) > 1)
        r.fail("'" + r.path() + "' must give one of 'gain', 'gain_db' or 'iso' (with 'base_iso')");
    x.gain = r.number("gain", 1.0, 1e-3, 1e4);
    if (r.has("gain_db")) {
        x.gainDb = r.number("gain_db", 0.0, -60.0, 80.0);
        x.gain = exactExp2(*x.gainDb * kLog2TenOver20); // 10^(dB / 20) without a libm call
    }
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
    } else if (x.gainDb) {
        json["gain_db"] = *x.gainDb;
    } else if (x.gain != 1.0) {
        json["gain"] = x.gain;
    }
    if (x.readNoiseAfterGain != 0.0) json["read_noise_after_gain"] = x.readNoiseAfterGain;
    if (x.blackLevel) json["black_level"] = *x.blackLevel;
    if (x.whiteBalance != std::array<double, 3>{1.0, 1.0, 1.0})
        json["white_balance"] = {x.whiteBalance[0], x.whiteBalance[1], x.whiteBalance[2]};
}

} // namespace sward
