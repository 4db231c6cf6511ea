// Reading a sward dataset for sward-export: its camera (frames.jsonl), the frames present, and each frame's
// ground truth and previews. Every function throws one sward::Error naming the file and the problem.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sward {

// The rectified rig as frames.jsonl gives it: OpenCV pixel centres (cx, cy of calib.txt), metres.
struct ExportCamera {
    double fx = 0, fy = 0, cx = 0, cy = 0;
    uint32_t width = 0, height = 0;
    double baseline = 0; // 0 for a mono dataset
    // The sensor model's lens distortion of the colour images (OpenCV k1, k2, p1, p2, k3); the ground truth is
    // never distorted (scene/sensor_model.h).
    std::array<double, 5> distortion{};
    bool distorted() const { return distortion != std::array<double, 5>{}; }
};

struct ExportFrame {
    uint32_t frame = 0;
    glm::dmat4 leftPose{1.0}, rightPose{1.0}; // camera-to-world, OpenCV camera axes
};

struct ExportDataset {
    std::string dir;
    bool stereo = false;
    ExportCamera camera;
    std::vector<ExportFrame> frames; // the frames whose depth file exists, in order
};

// Opens the dataset at `dir` (dataset.json must say it is one) and lists the frames of `range` ([first, end);
// all when empty) that were rendered. Throws when there is none.
ExportDataset openExportDataset(const std::string& dir, std::optional<std::pair<uint32_t, uint32_t>> range);

// One frame's ground truth, top row first.
struct FrameTruth {
    uint32_t width = 0, height = 0;
    std::vector<float> depth;       // planar metres, +inf for sky
    std::vector<uint8_t> semantic;  // class id
    std::vector<uint32_t> instance; // instance id
    std::vector<uint8_t> rgb;       // the tonemapped left preview, 8-bit sRGB, 3 per pixel
    std::vector<float> normal;      // unit normals in left camera axes, 3 per pixel; empty when the dataset has
                                    // no normal/ files (written before normals existed)
};
FrameTruth readFrameTruth(const ExportDataset& dataset, uint32_t frame);

// Throws when the colour images are distorted: `layout` pairs them pixel for pixel with the undistorted truth.
void requireUndistorted(const ExportDataset& dataset, const char* layout);

// The left disparity of a stereo frame (disparity/NNNNNN.pfm), 0 where there is none (sky).
std::vector<float> readFrameDisparity(const ExportDataset& dataset, uint32_t frame);

// occlusion/NNNNNN.png of a stereo frame: 255 visible in both views, 128 occluded, 0 no truth.
std::vector<uint8_t> readOcclusionMask(const ExportDataset& dataset, uint32_t frame);

// The bytes of a frame's PNG or PFM file for a lossless copy, decoded once first: a truncated or corrupt file,
// or one of another size than the frames, is refused rather than copied.
std::vector<char> readFrameFileBytes(const ExportDataset& dataset, const char* folder, uint32_t frame,
                                     const char* extension);
// calib.txt's bytes, parsed once first (its size must be the frames').
std::vector<char> readCalibBytes(const ExportDataset& dataset);

} // namespace sward
