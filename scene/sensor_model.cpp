#include "scene/sensor_model.h"

#include "world/camera.h"
#include "common/error.h"
#include "common/half_float.h"
#include "common/hash.h"
#include "common/json_reader.h"
#include "scene/sensor_raw.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

namespace {

// Distinguishes sensor noise from every other hashed quantity that might share (seed, frame, ...) keys.
constexpr uint64_t kSensorNoiseDomain = 0x53454e534f524e31ull; // "SENSORN1"

// Standard normal for one pixel channel, from one counter-based hash.
double gaussian(uint64_t seed, uint32_t frame, uint32_t camera, uint64_t pixel, uint32_t channel) {
    return standardNormal(hashKey({kSensorNoiseDomain, seed, frame, camera, pixel, channel}));
}

// Jacobian of distortNormalized at (x, y), row-major.
void distortJacobian(const SensorParams& p, double x, double y, double j[4]) {
    double r2 = x * x + y * y;
    double radial = 1.0 + r2 * (p.k1 + r2 * (p.k2 + r2 * p.k3));
    double dRadial = p.k1 + r2 * (2.0 * p.k2 + 3.0 * r2 * p.k3); // d radial / d r2
    j[0] = radial + 2.0 * x * x * dRadial + 2.0 * p.p1 * y + 6.0 * p.p2 * x;
    j[1] = 2.0 * x * y * dRadial + 2.0 * p.p1 * x + 2.0 * p.p2 * y;
    j[2] = 2.0 * x * y * dRadial + 2.0 * p.p1 * x + 2.0 * p.p2 * y;
    j[3] = radial + 2.0 * y * y * dRadial + 6.0 * p.p1 * y + 2.0 * p.p2 * x;
}

} // namespace

Intrinsics Intrinsics::of(const Camera& camera) {
    return {camera.fx, camera.fy, camera.cx, camera.cy, camera.width, camera.height};
}

void distortNormalized(const SensorParams& p, double x, double y, double& xd, double& yd) {
    double r2 = x * x + y * y;
    double radial = 1.0 + r2 * (p.k1 + r2 * (p.k2 + r2 * p.k3));
    xd = x * radial + 2.0 * p.p1 * x * y + p.p2 * (r2 + 2.0 * x * x);
    yd = y * radial + p.p1 * (r2 + 2.0 * y * y) + 2.0 * p.p2 * x * y;
}

void undistortNormalized(const SensorParams& p, double xd, double yd, double& x, double& y) {
    // Newton from the distorted point converges in a few steps for any lens that is invertible over the
    // image; the iteration count is bounded, so the result is deterministic.
    x = xd;
    y = yd;
    for (int i = 0; i < 20; ++i) {
        double fx, fy, j[4];
        distortNormalized(p, x, y, fx, fy);
        fx -= xd;
        fy -= yd;
        distortJacobian(p, x, y, j);
        double det = j[0] * j[3] - j[1] * j[2];
        if (!(std::abs(det) > 1e-12)) break;
        double dx = (j[3] * fx - j[1] * fy) / det;
        double dy = (j[0] * fy - j[2] * fx) / det;
        x -= dx;
        y -= dy;
        if (std::abs(dx) + std::abs(dy) < 1e-15) break;
    }
}

SensorModel::SensorModel(const SensorParams& params, const Intrinsics& in) : params_(params), intrinsics_(in) {
    if (!params_.enabled) return;
    require(in.width > 0 && in.height > 0 && in.fx > 0.0 && in.fy > 0.0, "sensor model: invalid camera intrinsics");
    checkOptics(params_.optics, in); // the sensor is built before anything is written: refuse a bad lens here
    size_t pixels = size_t(in.width) * in.height;
    gain_.resize(pixels);
    if (params_.hasDistortion()) sourceUv_.resize(pixels * 2);
    for (uint32_t j = 0; j < in.height; ++j) {
        for (uint32_t i = 0; i < in.width; ++i) {
            size_t p = size_t(j) * in.width + i;
            double xd = (i + 0.5 - in.cx) / in.fx, yd = (j + 0.5 - in.cy) / in.fy;
            double x = xd, y = yd;
            if (params_.hasDistortion()) {
                undistortNormalized(params_, xd, yd, x, y);
                // A lens model that folds over inside the image (strong k with large r) has no unique ideal
                // point for this pixel; refuse it rather than render a plausible-looking wrong image.
                double cx, cy, jac[4];
                distortNormalized(params_, x, y, cx, cy);
                distortJacobian(params_, x, y, jac);
                if (!(std::abs(cx - xd) + std::abs(cy - yd) < 1e-9) || !(jac[0] * jac[3] - jac[1] * jac[2] > 0.0))
                    throw Error("sensor model: the lens distortion (k1, k2, k3, p1, p2) is not invertible at pixel (" +
                                std::to_string(i) + ", " + std::to_string(j) + "); reduce the coefficients");
                // Sample position in array index space (pixel centres at integer + 0.5 in camera.h's convention).
                sourceUv_[p * 2 + 0] = float(in.fx * x + in.cx - 0.5);
                sourceUv_[p * 2 + 1] = float(in.fy * y + in.cy - 0.5);
            }
            // Natural vignetting from the chief ray's angle to the axis: cos^2 = 1 / (1 + x^2 + y^2).
            double cos2 = 1.0 / (1.0 + x * x + y * y);
            gain_[p] = float(params_.exposure * (1.0 - params_.vignetting + params_.vignetting * cos2 * cos2));
        }
    }
}

void SensorModel::apply(uint64_t seed, uint32_t frame, uint32_t camera, std::span<float> rgba,
                        double exposureScale) const {
    if (!params_.enabled) return;
    const uint32_t w = intrinsics_.width, h = intrinsics_.height;
    require(rgba.size() == size_t(w) * h * 4, "sensor model: image size does not match the camera");

    if (!sourceUv_.empty()) {
        std::vector<float> ideal(rgba.begin(), rgba.end());
        auto texel = [&](int32_t i, int32_t j, int c) {
            i = std::clamp<int32_t>(i, 0, int32_t(w) - 1);
            j = std::clamp<int32_t>(j, 0, int32_t(h) - 1);
            return ideal[(size_t(j) * w + uint32_t(i)) * 4 + c];
        };
        for (size_t p = 0; p < size_t(w) * h; ++p) {
            float sx = sourceUv_[p * 2], sy = sourceUv_[p * 2 + 1];
            float fx = std::floor(sx), fy = std::floor(sy);
            float tx = sx - fx, ty = sy - fy;
            // Zero weights skip their texel, so an infinite neighbour cannot turn an exact sample into NaN.
            auto lerp = [](float a, float b, float t) { return t == 0.0f ? a : a * (1.0f - t) + b * t; };
            int32_t i0 = int32_t(std::clamp(fx, -2.0f, float(w))), j0 = int32_t(std::clamp(fy, -2.0f, float(h)));
            for (int c = 0; c < 4; ++c) {
                float top = lerp(texel(i0, j0, c), texel(i0 + 1, j0, c), tx);
                float bottom = lerp(texel(i0, j0 + 1, c), texel(i0 + 1, j0 + 1, c), tx);
                rgba[p * 4 + c] = lerp(top, bottom, ty);
            }
        }
    }

    const double epu = params_.electronsPerUnit;
    const bool mosaic = params_.cfa.enabled(); // one colour per photosite, demosaiced below (scene/sensor_bayer.h)
    for (size_t p = 0; p < size_t(w) * h; ++p) {
        for (uint32_t c = 0; c < 3; ++c) {
            if (mosaic && c != bayerChannel(params_.cfa.pattern, uint32_t(p % w), uint32_t(p / w))) continue;
            float& value = rgba[p * 4 + c];
            value *= gain_[p];
            if (exposureScale != 1.0) value = float(double(value) * exposureScale); // auto-exposure
            if (epu > 0.0 || !params_.electronics.isDefault()) {
                const double normal = epu > 0.0 && std::isfinite(value) ? gaussian(seed, frame, camera, p, c) : 0.0;
                value = float(sensorReadout(params_, value, c, normal));
            }
        }
    }
    if (mosaic) demosaic(params_.cfa, w, h, rgba);
}

void SensorModel::applyHalf(uint64_t seed, uint32_t frame, uint32_t camera, std::span<uint16_t> rgbaHalf,
                            double exposureScale, std::vector<uint16_t>* digital) const {
    if (!params_.enabled) return;
    std::vector<float> rgba(rgbaHalf.size());
    std::transform(rgbaHalf.begin(), rgbaHalf.end(), rgba.begin(), halfBitsToFloat);
    apply(seed, frame, camera, rgba, exposureScale);
    if (digital && params_.bitDepth != 0) // the ADC reads the float signal
        *digital = rawDigitalImage(params_, rgba, intrinsics_.width);
    std::transform(rgba.begin(), rgba.end(), rgbaHalf.begin(), floatToHalfBits);
}

void applySensor(const SensorParams& params, const Intrinsics& intrinsics, uint64_t seed, uint32_t frame,
                 uint32_t camera, std::span<float> rgba) {
    SensorModel(params, intrinsics).apply(seed, frame, camera, rgba);
}

void applySensorHalf(const SensorParams& params, const Intrinsics& intrinsics, uint64_t seed, uint32_t frame,
                     uint32_t camera, std::span<uint16_t> rgbaHalf) {
    SensorModel(params, intrinsics).applyHalf(seed, frame, camera, rgbaHalf);
}

SensorParams parseSensor(const nlohmann::json& json, const std::string& source, const std::string& jsonPath) {
    SensorParams p;
    if (json.is_null()) return p;
    JsonReader r(json, source, jsonPath);
    constexpr double kBig = 1e6;
    p.enabled = r.boolean("enabled", true);
    if (r.has("exposure") && r.has("exposure_ev"))
        r.fail("'" + jsonPath + "' must give either 'exposure' or 'exposure_ev', not both");
    p.exposure = r.number("exposure", 1.0, 1e-9, 1e9);
    if (r.has("exposure_ev")) p.exposure = std::exp2(r.number("exposure_ev", 0.0, -30.0, 30.0));
    p.vignetting = r.number("vignetting", 0.0, 0.0, 1.0);
    p.k1 = r.number("k1", 0.0, -kBig, kBig);
    p.k2 = r.number("k2", 0.0, -kBig, kBig);
    p.k3 = r.number("k3", 0.0, -kBig, kBig);
    p.p1 = r.number("p1", 0.0, -kBig, kBig);
    p.p2 = r.number("p2", 0.0, -kBig, kBig);
    p.electronsPerUnit = r.number("electrons_per_unit", 0.0, 0.0, 1e12);
    p.readNoise = r.number("read_noise", 0.0, 0.0, 1e9);
    p.fullWell = r.number("full_well", 0.0, 0.0, 1e15);
    if ((p.readNoise > 0.0 || p.fullWell > 0.0) && p.electronsPerUnit <= 0.0)
        r.fail(r.name("electrons_per_unit") + " must be positive when 'read_noise' or 'full_well' is set");
    p.shutterSeconds = r.number("shutter_s", 0.0, 0.0, kMaxShutterSeconds);
    if (const nlohmann::json* samples = r.raw("motion_samples"); samples && *samples != "auto") {
        const bool whole = samples->is_number_unsigned() || (samples->is_number_integer() && *samples >= 0);
        if (!whole || *samples == 1 || samples->get<uint64_t>() > kMaxMotionSamples)
            r.fail(r.name("motion_samples") + " must be \"auto\", 0 (auto) or an integer in [2, " +
                   std::to_string(kMaxMotionSamples) + "] (got " + samples->dump() + ")");
        p.motionSamples = samples->get<uint32_t>();
    }
    p.readoutSeconds = r.number("readout_s", 0.0, 0.0, kMaxReadoutSeconds);
    p.readoutBands = uint32_t(r.integer("readout_bands", 0, 1, kMaxReadoutBands));
    p.stereoOffsetSeconds = r.number("stereo_offset_s", 0.0, -kMaxStereoOffsetSeconds, kMaxStereoOffsetSeconds);
    parseSensorElectronics(r, p);
    p.autoExposure = parseAutoExposure(r);
    parseLensOptics(r, p.optics);
    parseRawBitDepth(r, p);
    parseColourFilterArray(r, p);
    r.finish();
    return p;
}

nlohmann::json sensorToJson(const SensorParams& p) {
    nlohmann::json json = {{"enabled", p.enabled},
                           {"exposure", p.exposure},
                           {"vignetting", p.vignetting},
                           {"k1", p.k1},
                           {"k2", p.k2},
                           {"k3", p.k3},
                           {"p1", p.p1},
                           {"p2", p.p2},
                           {"electrons_per_unit", p.electronsPerUnit},
                           {"read_noise", p.readNoise},
                           {"full_well", p.fullWell}};
    sensorElectronicsToJson(p.electronics, json);
    lensOpticsToJson(p.optics, json);
    if (p.bitDepth != 0) json["bit_depth"] = p.bitDepth; // absent without a digital output: records as before
    colourFilterArrayToJson(p.cfa, json);                // absent without a Bayer pattern: records as before
    if (p.autoExposure.enabled) json["auto_exposure"] = autoExposureToJson(p.autoExposure); // absent: as before
    if (p.shutterSeconds > 0.0) { // absent from a scene without a shutter: its records stay as they were
        json["shutter_s"] = p.shutterSeconds;
        json["motion_samples"] = p.motionSamples == 0 ? nlohmann::json("auto") : nlohmann::json(p.motionSamples);
    }
    if (p.readoutSeconds > 0.0) { // absent with a global shutter: its records stay as they were
        json["readout_s"] = p.readoutSeconds;
        if (p.readoutBands != 0) json["readout_bands"] = p.readoutBands; // absent: every row its own band
    }
    if (p.stereoOffsetSeconds != 0.0) json["stereo_offset_s"] = p.stereoOffsetSeconds; // absent: synchronised
    return json;
}

} // namespace sward
