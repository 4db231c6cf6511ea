// Optical-flow files in the formats flow benchmarks use: Middlebury .flo (Sintel, Middlebury, FlyingChairs) and the
// KITTI 2015 16-bit flow PNG (docs/dataset-format.md, "Optical flow").
//
// In memory a flow field is width*height (u, v) pairs in pixels, row-major, TOP row first: the displacement from a
// pixel's centre in the source frame to its centre in the target frame. "No value" (sky, or a pixel a method did
// not estimate) is NaN; the file formats encode it differently (.flo: |value| > 1e9, KITTI: valid bit 0) and the
// readers and writers translate, so callers only ever see NaN.
//
// Every writer is atomic; every reader throws sward::Error naming the file and the problem, checks the header
// against the file's size before allocating anything, and never reads past the data.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace sward {

struct FlowField {
    uint32_t width = 0, height = 0;
    std::vector<float> uv; // u0, v0, u1, v1, ...: 2 * width * height values, NaN = no value

    float u(size_t pixel) const { return uv[2 * pixel]; }
    float v(size_t pixel) const { return uv[2 * pixel + 1]; }
};

// Middlebury's "unknown flow" threshold: a component above it in magnitude is no value.
inline constexpr float kUnknownFlowThreshold = 1e9f;
// What .flo files hold for an unknown component (Middlebury's UNKNOWN_FLOW).
inline constexpr float kUnknownFlowValue = 1e10f;
// The .flo tag: the float 202021.25, whose little-endian bytes spell "PIEH".
inline constexpr float kFloTag = 202021.25f;

// True for a usable flow vector: both components finite and at most kUnknownFlowThreshold in magnitude.
inline bool isValidFlow(float u, float v) {
    return std::isfinite(u) && std::isfinite(v) && std::abs(u) <= kUnknownFlowThreshold &&
           std::abs(v) <= kUnknownFlowThreshold;
}

// .flo: float32 tag 202021.25, int32 width, int32 height, then (u, v) float32 pairs, top row first, all
// little-endian. Invalid vectors are written as kUnknownFlowValue in both components.
void writeFlo(const std::string& path, const FlowField& flow);
// Reads a .flo file whose size is exactly 12 + 8 * width * height bytes, edges 1..kMaxImageEdge. Components beyond
// kUnknownFlowThreshold (or non-finite) make the vector NaN.
FlowField readFlo(const std::string& path);

// KITTI flow PNG: 16-bit RGB, R = round(u * 64) + 32768, G = round(v * 64) + 32768, B = 1 valid / 0 invalid.
// Vectors whose components do not fit (u * 64 outside -32768..32767) are written as invalid.
void writeKittiFlowPng(const std::string& path, const FlowField& flow);
FlowField readKittiFlowPng(const std::string& path);

// Reads either format by extension (.flo or .png); throws for another extension.
FlowField readFlow(const std::string& path);

} // namespace sward
