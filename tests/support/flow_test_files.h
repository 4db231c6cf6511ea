// A tiny synthetic optical-flow dataset laid out like sward-render's output with render.flow (docs/dataset-format.md):
// preview/ frames that are one smooth texture translated by a known sub-pixel step per frame, so the true forward
// flow is that step everywhere, with flow_forward/, flow_forward_mask/, semantic/ and depth/ written to match.
#pragma once

#include "common/hash.h"
#include "dataset/naming.h"
#include "io/flow_files.h"
#include "io/image_files.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

namespace sward::test {

struct FlowDataset {
    uint32_t width = 160, height = 120;
    uint32_t frames = 3;          // previews and flow truth 0 .. frames-1; the last frame's target is not rendered
    float u = 1.5f, v = -0.75f;   // the true flow of every pixel with truth (multiples of 1/64: exact in KITTI PNG)
    uint32_t skyRows = 10;        // the top rows have no truth (sky)
    uint32_t occludedColumns = 4; // the right-most columns leave the view: mask 128
    float nearDepth = 2, farDepth = 30; // depth/ of the bottom and the top half (bands 0-5 m and 20-50 m)
    uint64_t seed = 1;
};

// Smooth random texture: value noise on an 8 px lattice, bilinear, two octaves, per channel; evaluated at real
// coordinates, so a translated frame is the exact translated texture.
inline double flowTexture(const FlowDataset& s, double x, double y, int channel) {
    auto lattice = [&](int64_t i, int64_t j, uint64_t octave) {
        return unitDouble(hashKey({s.seed, octave, uint64_t(i + 1000000), uint64_t(j + 1000000), uint64_t(channel)}));
    };
    double value = 0, weight = 0;
    for (uint64_t octave = 0; octave < 2; ++octave) {
        const double cell = octave == 0 ? 8.0 : 3.0, gx = x / cell, gy = y / cell;
        const double fx = std::floor(gx), fy = std::floor(gy), tx = gx - fx, ty = gy - fy;
        const int64_t i = int64_t(fx), j = int64_t(fy);
        const double top = lattice(i, j, octave) * (1 - tx) + lattice(i + 1, j, octave) * tx;
        const double bottom = lattice(i, j + 1, octave) * (1 - tx) + lattice(i + 1, j + 1, octave) * tx;
        const double w = octave == 0 ? 1.0 : 0.5;
        value += w * (top * (1 - ty) + bottom * ty);
        weight += w;
    }
    return value / weight;
}

// The forward flow truth every frame gets: (u, v) except sky.
inline FlowField flowTruth(const FlowDataset& s) {
    FlowField flow{s.width, s.height, std::vector<float>(2 * size_t(s.width) * s.height)};
    for (uint32_t y = 0; y < s.height; ++y)
        for (uint32_t x = 0; x < s.width; ++x) {
            const size_t i = size_t(y) * s.width + x;
            const bool sky = y < s.skyRows;
            flow.uv[2 * i] = sky ? std::numeric_limits<float>::quiet_NaN() : s.u;
            flow.uv[2 * i + 1] = sky ? std::numeric_limits<float>::quiet_NaN() : s.v;
        }
    return flow;
}

// Writes preview/, flow_forward/ (.flo and KITTI .png), flow_forward_mask/, semantic/ (left half ground 1, right
// half vegetation 3, sky 0) and depth/ (Y + Z, +inf sky) into `dir`.
inline void writeFlowDataset(const std::string& dir, const FlowDataset& s) {
    namespace fs = std::filesystem;
    for (const char* sub : {kPreviewFolder, kFlowForwardFolder, kFlowForwardMaskFolder, kSemanticFolder, kDepthFolder})
        fs::create_directories(dir + "/" + sub);
    const FlowField truth = flowTruth(s);
    for (uint32_t frame = 0; frame < s.frames; ++frame) {
        cv::Mat preview(int(s.height), int(s.width), CV_8UC3), semantic(int(s.height), int(s.width), CV_8UC1);
        cv::Mat mask(int(s.height), int(s.width), CV_8UC1);
        std::vector<float> depth(size_t(s.width) * s.height);
        for (int y = 0; y < int(s.height); ++y)
            for (int x = 0; x < int(s.width); ++x) {
                // Frame k shows the texture moved by k * (u, v): the pixel at p + (u, v) in frame k+1 shows what p
                // showed in frame k.
                for (int c = 0; c < 3; ++c)
                    preview.at<cv::Vec3b>(y, x)[c] = uint8_t(
                        std::lround(255.0 * flowTexture(s, x - double(frame) * s.u, y - double(frame) * s.v, c)));
                const bool sky = y < int(s.skyRows);
                semantic.at<uint8_t>(y, x) = sky ? 0 : (x < int(s.width / 2) ? 1 : 3);
                mask.at<uint8_t>(y, x) = sky ? 0 : x >= int(s.width - s.occludedColumns) ? 128 : 255;
                depth[size_t(y) * s.width + x] = sky ? INFINITY : (y >= int(s.height / 2) ? s.nearDepth : s.farDepth);
            }
        auto path = [&](const char* folder, const char* extension) {
            return dir + "/" + frameFile(folder, frame, extension);
        };
        cv::imwrite(path(kPreviewFolder, ".png"), preview);
        cv::imwrite(path(kSemanticFolder, ".png"), semantic);
        cv::imwrite(path(kFlowForwardMaskFolder, ".png"), mask);
        writeExrDepth(path(kDepthFolder, ".exr"), s.width, s.height, depth);
        writeFlo(path(kFlowForwardFolder, ".flo"), truth);
        writeKittiFlowPng(path(kFlowForwardFolder, ".png"), truth);
    }
}

// A method's output: the truth plus `error(x, y)` = (du, dv) at every pixel (sky too), as .flo files of frames
// 0 .. frames-2 in `dir`.
template <class Error> void writeFlowEstimates(const std::string& dir, const FlowDataset& s, Error error) {
    std::filesystem::create_directories(dir);
    for (uint32_t frame = 0; frame + 1 < s.frames; ++frame) {
        FlowField flow{s.width, s.height, std::vector<float>(2 * size_t(s.width) * s.height)};
        for (uint32_t y = 0; y < s.height; ++y)
            for (uint32_t x = 0; x < s.width; ++x) {
                const auto [du, dv] = error(x, y);
                const size_t i = size_t(y) * s.width + x;
                flow.uv[2 * i] = s.u + du;
                flow.uv[2 * i + 1] = s.v + dv;
            }
        writeFlo(dir + "/" + frameName(frame) + ".flo", flow);
    }
}

} // namespace sward::test
