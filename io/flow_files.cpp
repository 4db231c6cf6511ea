#include "io/flow_files.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "io/image_io.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace sward {

namespace {

constexpr float kFloTag = 202021.25f;

void requireShape(const std::string& path, const FlowField& flow) {
    const size_t pixels = size_t(flow.width) * flow.height;
    require(flow.width > 0 && flow.height > 0 && flow.uv.size() == 2 * pixels && flow.valid.size() == pixels,
            "cannot write '" + path + "': the flow field's size does not match its width and height");
}

template <typename T> T readLittle(const uint8_t* bytes) { // little_endian.h: sward builds for little-endian machines
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

} // namespace

void writeFlo(const std::string& path, const FlowField& flow) {
    requireShape(path, flow);
    std::string bytes;
    bytes.reserve(12 + flow.uv.size() * 4);
    appendLittleEndian(bytes, kFloTag, flow.width, flow.height);
    for (size_t i = 0; i < flow.valid.size(); ++i)
        for (size_t c = 0; c < 2; ++c) appendLittleEndian(bytes, flow.valid[i] ? flow.uv[2 * i + c] : kFloUnknown);
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

FlowField readFlo(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    require(bool(file), "cannot read '" + path + "'");
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    require(bytes.size() >= 12 && std::bit_cast<float>(readLittle<uint32_t>(bytes.data())) == kFloTag,
            path + ": not a Middlebury .flo file (no 202021.25 tag)");
    const int32_t width = readLittle<int32_t>(bytes.data() + 4), height = readLittle<int32_t>(bytes.data() + 8);
    require(width > 0 && height > 0 && width <= int32_t(kMaxImageEdge) && height <= int32_t(kMaxImageEdge),
            path + ": bad .flo size " + std::to_string(width) + " x " + std::to_string(height));
    FlowField flow{uint32_t(width), uint32_t(height), {}, {}};
    const size_t pixels = size_t(width) * size_t(height);
    require(bytes.size() == 12 + pixels * 8, path + ": a " + std::to_string(width) + " x " + std::to_string(height) +
                                                 " .flo file must hold " + std::to_string(12 + pixels * 8) +
                                                 " bytes, it holds " + std::to_string(bytes.size()));
    flow.uv.resize(2 * pixels);
    flow.valid.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const float u = std::bit_cast<float>(readLittle<uint32_t>(bytes.data() + 12 + 8 * i));
        const float v = std::bit_cast<float>(readLittle<uint32_t>(bytes.data() + 16 + 8 * i));
        const bool known = std::isfinite(u) && std::isfinite(v) && std::abs(u) <= kFloUnknownThreshold &&
                           std::abs(v) <= kFloUnknownThreshold;
        flow.valid[i] = known ? 1 : 0;
        flow.uv[2 * i] = known ? u : 0.0f;
        flow.uv[2 * i + 1] = known ? v : 0.0f;
    }
    return flow;
}

void writeKittiFlowPng(const std::string& path, const FlowField& flow) {
    requireShape(path, flow);
    cv::Mat image(int(flow.height), int(flow.width), CV_16UC3); // OpenCV's channel order: B, G, R
    const double limit = kKittiFlowLimit - 1.0 / 64.0;
    for (uint32_t y = 0; y < flow.height; ++y) {
        uint16_t* row = image.ptr<uint16_t>(int(y));
        for (uint32_t x = 0; x < flow.width; ++x) {
            const size_t i = size_t(y) * flow.width + x;
            const double u = flow.uv[2 * i], v = flow.uv[2 * i + 1];
            const bool fits = flow.valid[i] && std::abs(u) <= limit && std::abs(v) <= limit;
            row[3 * x + 2] = fits ? uint16_t(std::lround(u * 64.0 + 32768.0)) : 0;
            row[3 * x + 1] = fits ? uint16_t(std::lround(v * 64.0 + 32768.0)) : 0;
            row[3 * x + 0] = fits ? 1 : 0;
        }
    }
    std::vector<uint8_t> bytes;
    require(cv::imencode(".png", image, bytes), "cannot write '" + path + "': PNG encoding failed");
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

FlowField readKittiFlowPng(const std::string& path) {
    const ImageData image = loadImage(path); // sward's reader: the header is checked against the file first
    require(image.bitDepth == 16 && image.channels == 3,
            path + ": a KITTI flow PNG must be 16-bit with 3 channels (found " + std::to_string(image.bitDepth) +
                "-bit, " + std::to_string(image.channels) + " channel(s))");
    FlowField flow{image.width, image.height, {}, {}};
    const size_t pixels = size_t(image.width) * image.height;
    flow.uv.resize(2 * pixels);
    flow.valid.resize(pixels);
    // Samples are value / 65535 in float; the 16-bit value comes back exactly by rounding.
    auto value = [&](size_t i, uint32_t c) { return double(std::lround(double(image.samples[3 * i + c]) * 65535.0)); };
    for (size_t i = 0; i < pixels; ++i) {
        flow.valid[i] = value(i, 2) != 0.0 ? 1 : 0;
        flow.uv[2 * i] = flow.valid[i] ? float((value(i, 0) - 32768.0) / 64.0) : 0.0f;
        flow.uv[2 * i + 1] = flow.valid[i] ? float((value(i, 1) - 32768.0) / 64.0) : 0.0f;
    }
    return flow;
}

} // namespace sward
