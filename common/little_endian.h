// Binary files in little-endian byte order (PLY binary_little_endian, KITTI .bin, SemanticKITTI .label): values
// appended as their native bytes, which are little-endian on every machine sward builds for.
#pragma once

#include <bit>
#include <cstring>
#include <string>

namespace sward {

static_assert(std::endian::native == std::endian::little, "sward's binary writers assume a little-endian machine");

// Appends each value's bytes, in order.
template <typename... T> void appendLittleEndian(std::string& bytes, T... values) {
    auto one = [&bytes](auto value) {
        char raw[sizeof(value)];
        std::memcpy(raw, &value, sizeof(value));
        bytes.append(raw, sizeof(value));
    };
    (one(values), ...);
}

} // namespace sward
