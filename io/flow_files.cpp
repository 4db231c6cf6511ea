#include "io/flow_files.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace sward {

namespace {

// KITTI's flow PNG: 1/64 px steps around 32768.
constexpr double kKittiFlowScale = 64.0;
constexpr double kKittiFlowOffset = 32768.0;

void requireFlowSize(const std::string& path, const FlowField& flow) {
    require(flow.width > 0 && flow.height > 0 && flow.width <= kMaxImageEdge && flow.height <= kMaxImageEdge,
            "cannot write '" + path + "': flow field of " + std::to_string(flow.width) + "x" +
                std::to_string(flow.height) + " is empty or too large");
    require(flow.uv.size() == 2 * size_t(flow.width) * flow.height,
            "cannot write '" + path + "': flow has " + std::to_string(flow.uv.size()) + " values, expected 2 x " +
                std::to_string(flow.width) + "x" + std::to_string(flow.height));
}

// The file is little-endian whatever the machine: 4 bytes of `bits` at `out`.
void putLittle32(char* out, uint32_t bits) {
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
    std::memcpy(out, &bits, 4);
}

uint32_t getLittle32(const char* in) {
    uint32_t bits;
    std::memcpy(&bits, in, 4);
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
    return bits;
}

// The file's size, checked against `expected` before anything is read or allocated: a header that claims more
// than the file holds is "truncated", one that claims less has trailing bytes.
void requireFloSize(const std::string& path, int32_t width, int32_t height) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    require(!ec, "cannot read '" + path + "': " + ec.message());
    const uint64_t expected = 12 + 8 * uint64_t(width) * uint64_t(height);
    require(size >= expected, path + ": .flo is truncated: " + std::to_string(width) + "x" + std::to_string(height) +
                                  " needs " + std::to_string(expected) + " bytes, the file has " +
                                  std::to_string(size));
    require(size == expected, path + ": .flo has " + std::to_string(size - expected) + " bytes after the " +
                                  std::to_string(width) + "x" + std::to_string(height) + " flow its header announces");
}

} // namespace

void writeFlo(const std::string& path, const FlowField& flow) {
    requireFlowSize(path, flow);
    std::string data(12 + 4 * flow.uv.size(), '\0');
    putLittle32(data.data(), std::bit_cast<uint32_t>(kFloTag));
    putLittle32(data.data() + 4, flow.width);
    putLittle32(data.data() + 8, flow.height);
    char* out = data.data() + 12;
    for (size_t i = 0; i < flow.uv.size(); i += 2) {
        const bool valid = isValidFlow(flow.uv[i], flow.uv[i + 1]);
        putLittle32(out, std::bit_cast<uint32_t>(valid ? flow.uv[i] : kUnknownFlowValue));
        putLittle32(out + 4, std::bit_cast<uint32_t>(valid ? flow.uv[i + 1] : kUnknownFlowValue));
        out += 8;
    }
    writeBytesAtomically(path, data.data(), data.size());
}

FlowField readFlo(const std::string& path) {
    std::error_code ec;
    require(std::filesystem::is_regular_file(path, ec), "cannot open '" + path + "': no such file");
    std::ifstream file(path, std::ios::binary);
    require(bool(file), "cannot open '" + path + "': permission denied");
    char header[12];
    require(bool(file.read(header, 12)), path + ": .flo is truncated: shorter than its 12-byte header");
    require(getLittle32(header) == std::bit_cast<uint32_t>(kFloTag),
            path + ": not a .flo file (the first 4 bytes are not the tag \"PIEH\", 202021.25)");
    const int32_t width = int32_t(getLittle32(header + 4)), height = int32_t(getLittle32(header + 8));
    require(width > 0 && height > 0 && uint32_t(width) <= kMaxImageEdge && uint32_t(height) <= kMaxImageEdge,
            path + ": .flo size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range (1.." +
                std::to_string(kMaxImageEdge) + ")");
    requireFloSize(path, width, height);
    FlowField flow{uint32_t(width), uint32_t(height), std::vector<float>(2 * size_t(width) * size_t(height))};
    std::vector<char> data(flow.uv.size() * 4);
    require(bool(file.read(data.data(), std::streamsize(data.size()))), "cannot read '" + path + "'");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t i = 0; i < flow.uv.size(); i += 2) {
        const float u = std::bit_cast<float>(getLittle32(data.data() + 4 * i));
        const float v = std::bit_cast<float>(getLittle32(data.data() + 4 * i + 4));
        const bool valid = isValidFlow(u, v);
        flow.uv[i] = valid ? u : nan;
        flow.uv[i + 1] = valid ? v : nan;
    }
    return flow;
}

void writeKittiFlowPng(const std::string& path, const FlowField& flow) {
    requireFlowSize(path, flow);
    std::vector<uint16_t> rgb(size_t(flow.width) * flow.height * 3, 0); // R = u, G = v, B = valid
    for (size_t i = 0; i < size_t(flow.width) * flow.height; ++i) {
        const double u = std::round(double(flow.u(i)) * kKittiFlowScale) + kKittiFlowOffset;
        const double v = std::round(double(flow.v(i)) * kKittiFlowScale) + kKittiFlowOffset;
        if (!isValidFlow(flow.u(i), flow.v(i)) || u < 0 || u > 65535 || v < 0 || v > 65535) continue;
        rgb[3 * i] = uint16_t(u);
        rgb[3 * i + 1] = uint16_t(v);
        rgb[3 * i + 2] = 1;
    }
    writePng16(path, flow.width, flow.height, 3, rgb);
}

FlowField readKittiFlowPng(const std::string& path) {
    // sward's PNG reader, not cv::imread: it checks the header against the file before allocating (disparity_files).
    const ImageData image = loadImage(path);
    require(image.bitDepth == 16 && image.channels == 3,
            path + ": a KITTI flow PNG must be 16-bit with 3 channels (found " + std::to_string(image.bitDepth) +
                "-bit, " + std::to_string(image.channels) + " channel(s))");
    FlowField flow{image.width, image.height, std::vector<float>(2 * size_t(image.width) * image.height)};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // Samples are value / 65535 in float; the 16-bit value comes back exactly by rounding.
    auto value = [&](size_t sample) { return double(std::lround(image.samples[sample] * 65535.0f)); };
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
        const bool valid = value(3 * i + 2) != 0;
        flow.uv[2 * i] = valid ? float((value(3 * i) - kKittiFlowOffset) / kKittiFlowScale) : nan;
        flow.uv[2 * i + 1] = valid ? float((value(3 * i + 1) - kKittiFlowOffset) / kKittiFlowScale) : nan;
    }
    return flow;
}

FlowField readFlow(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "flo") return readFlo(path);
    if (ext == "png") return readKittiFlowPng(path);
    throw Error(path + ": unknown flow format '" + (ext.empty() ? "" : "." + ext) + "' (expected .flo or KITTI .png)");
}

} // namespace sward
