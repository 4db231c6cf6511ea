// Optical-flow files: Middlebury .flo and KITTI 2015 flow PNG, written by the dataset writer (render.flow) and read
// by the evaluation. A flow vector (u, v) is in pixels: the target pixel centre minus the source pixel centre.
//
// Writers encode the whole file in memory and write it atomically (common/atomic_file.h); readers check the header
// against the file's size before reading anything, and every error names the file.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

// Middlebury's "unknown flow": a component above this (in magnitude) means the pixel has no flow.
inline constexpr float kFloUnknownThreshold = 1e9f;
inline constexpr float kFloUnknown = 1e10f; // what the writer stores for a pixel without flow
// KITTI's flow PNG holds u * 64 + 2^15 in 16 bits: flows beyond this magnitude (pixels) cannot be stored.
inline constexpr double kKittiFlowLimit = 512.0;

struct FlowField {
    uint32_t width = 0, height = 0;
    std::vector<float> uv;     // width*height*2, top row first
    std::vector<uint8_t> valid; // width*height: 1 where the pixel has flow
};

// .flo: the float 202021.25 ("PIEH"), int32 width, int32 height, then (u, v) float32 per pixel, row by row, top row
// first, little-endian. Pixels that are not `valid` get kFloUnknown.
void writeFlo(const std::string& path, const FlowField& flow);
FlowField readFlo(const std::string& path);

// KITTI flow PNG: 16-bit RGB, R = u * 64 + 2^15, G = v * 64 + 2^15 (rounded), B = 1 valid / 0 invalid. Valid pixels
// whose flow does not fit (|u| or |v| >= kKittiFlowLimit - 1/64) are written invalid: the format cannot hold them.
void writeKittiFlowPng(const std::string& path, const FlowField& flow);
FlowField readKittiFlowPng(const std::string& path);

} // namespace sward
