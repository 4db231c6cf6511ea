// A 3 x 3 m flat plate as a glTF (one node, both faces), for tests that need a simple rigid object.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace sward::test {

// Writes `dir`/plate.gltf (embedded buffer) and returns its path.
inline std::string writePlate(const std::string& dir) {
    const float p[12] = {-1.5f, 0, -1.5f, 1.5f, 0, -1.5f, 1.5f, 0, 1.5f, -1.5f, 0, 1.5f};
    const uint16_t idx[12] = {0, 2, 1, 0, 3, 2, 0, 1, 2, 0, 2, 3}; // up-facing pair, then down-facing pair
    std::vector<uint8_t> bytes(sizeof p + sizeof idx);
    std::memcpy(bytes.data(), p, sizeof p);
    std::memcpy(bytes.data() + sizeof p, idx, sizeof idx);
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (size_t i = 0; i < bytes.size(); i += 3) { // 72 bytes: a multiple of 3, no padding
        uint32_t v = uint32_t(bytes[i]) << 16 | uint32_t(bytes[i + 1]) << 8 | bytes[i + 2];
        for (int k = 0; k < 4; ++k) b64 += alphabet[(v >> (18 - 6 * k)) & 63];
    }
    const std::string path = dir + "/plate.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "plate", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-1.5, 0, -1.5], "max": [1.5, 0, 1.5]},
                      {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)"
                    << b64 << R"("}]})";
    return path;
}

} // namespace sward::test
