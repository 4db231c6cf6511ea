#include "scene/sensor_raw.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/sensor_model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

double rawWhiteLevel(const SensorParams& params) {
    if (params.fullWell <= 0.0) return 1.0;
    return params.electronics.blackLevel.value_or(0.0) + params.fullWell / params.electronsPerUnit;
}

uint16_t rawDigitalNumber(double signal, double whiteLevel, uint32_t bitDepth) {
    require(std::find(std::begin(kRawBitDepths), std::end(kRawBitDepths), bitDepth) != std::end(kRawBitDepths),
            "rawDigitalNumber: bit depth must be 8, 10, 12, 14 or 16");
    const double fullScale = double((uint32_t(1) << bitDepth) - 1);
    const double x = signal / whiteLevel;
    if (!(x > 0.0)) return 0; // also NaN: no signal the ADC could read
    if (x >= 1.0) return uint16_t(fullScale);
    return uint16_t(std::floor(x * fullScale + 0.5)); // x * fullScale + 0.5 <= fullScale + 0.5: no overflow
}

std::vector<uint16_t> rawDigitalImage(const SensorParams& params, std::span<const float> rgba, uint32_t width) {
    const double white = rawWhiteLevel(params);
    if (params.cfa.enabled()) { // the photosites' own channel: the mosaic a single-chip camera reads out
        require(width > 0 && rgba.size() % (size_t(width) * 4) == 0, "rawDigitalImage: image size does not match");
        const uint32_t height = uint32_t(rgba.size() / 4 / width);
        std::vector<uint16_t> dn;
        dn.reserve(size_t(width) * height);
        for (float signal : bayerMosaic(params.cfa.pattern, width, height, rgba))
            dn.push_back(rawDigitalNumber(signal, white, params.bitDepth));
        return dn;
    }
    std::vector<uint16_t> dn(rgba.size() / 4 * 3);
    for (size_t p = 0; p < rgba.size() / 4; ++p)
        for (size_t c = 0; c < 3; ++c) dn[p * 3 + c] = rawDigitalNumber(rgba[p * 4 + c], white, params.bitDepth);
    return dn;
}

void parseRawBitDepth(JsonReader& reader, SensorParams& params) {
    const nlohmann::json* value = reader.raw("bit_depth");
    if (!value) return;
    const bool whole = value->is_number_unsigned() || (value->is_number_integer() && *value >= 0);
    const uint64_t bits = whole ? value->get<uint64_t>() : 1;
    if (bits != 0 && std::find(std::begin(kRawBitDepths), std::end(kRawBitDepths), bits) == std::end(kRawBitDepths))
        reader.fail(reader.name("bit_depth") + " must be 0 (no digital output), 8, 10, 12, 14 or 16 (got " +
                    value->dump() + ")");
    params.bitDepth = uint32_t(bits);
    if (params.bitDepth != 0 && !params.enabled)
        reader.fail(reader.name("bit_depth") + " needs an enabled sensor (the sensor has 'enabled': false)");
}

} // namespace sward
