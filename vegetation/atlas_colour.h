// The atlas's 8-bit encodings (internal to the atlas files): sRGB colour and unorm alpha, and the sRGB decoding
// table that painting and mipmapping share, so every level of the chain rounds exactly as level 0 does.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace sward::atlas_detail {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Decoding table and the linear midpoints between consecutive codes: encoding by search in this table makes
// encode(decode(b)) == b for every byte, so mipmapping a flat colour never drifts.
struct SrgbTable {
    std::array<float, 256> toLinear{};
    std::array<float, 255> midpoints{};
};

inline const SrgbTable& srgbTable() {
    static const SrgbTable table = [] {
        SrgbTable t;
        for (int i = 0; i < 256; ++i) t.toLinear[i] = srgbToLinear(float(i) / 255.0f);
        for (int i = 0; i < 255; ++i) t.midpoints[i] = 0.5f * (t.toLinear[i] + t.toLinear[i + 1]);
        return t;
    }();
    return table;
}

inline uint8_t encodeSrgb(float linear) {
    const auto& m = srgbTable().midpoints;
    return uint8_t(std::upper_bound(m.begin(), m.end(), linear) - m.begin());
}

inline uint8_t encodeUnorm(float v) {
    return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

} // namespace sward::atlas_detail
