// Disparity and calibration files in the formats stereo benchmarks use: PFM (Middlebury 2014 / ETH3D),
// KITTI 16-bit PNG and Middlebury's calib.txt.
//
// In memory a disparity map is width*height floats, row-major, TOP row first, in pixels of the left (reference)
// view, with 0 meaning "no value" (sky, or a pixel a matcher did not estimate). The file formats encode "no value"
// differently (PFM: +inf, KITTI: 0); the readers and writers translate, so callers only ever see 0.
//
// Every writer is atomic (writes "<path>.tmp", then renames it over <path>); every reader throws sward::Error
// naming the file and the problem.
#pragma once

#include "common/atomic_file.h" // writeTextAtomically

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace sward {

struct DisparityMap {
    uint32_t width = 0, height = 0;
    std::vector<float> values; // top row first; 0 = invalid

    float at(uint32_t x, uint32_t y) const { return values[size_t(y) * width + x]; }
};

// True for a usable disparity value: finite and > 0. Zero, negative, NaN and inf all mean "no value".
inline bool isValidDisparity(float d) {
    return std::isfinite(d) && d > 0.0f;
}

// PFM: header "Pf\n<w> <h>\n-1\n", little-endian float32, rows stored bottom row first. Invalid pixels
// (see isValidDisparity) are written as +inf.
void writePfm(const std::string& path, uint32_t width, uint32_t height, std::span<const float> disparity);
// The same layout with every value as it is (any sign, inf, NaN): e.g. the flow's disparity change.
void writePfmValues(const std::string& path, uint32_t width, uint32_t height, std::span<const float> values);

// Reads a one-channel ("Pf") PFM of either byte order (scale < 0: little-endian, > 0: big-endian). A three-channel
// "PF" file is refused. Non-finite and non-positive values become 0.
DisparityMap readPfm(const std::string& path);

// KITTI 2012/2015 disparity PNG: uint16 grey, value = round(d * 256), 0 = invalid. Values that do not fit
// (d * 256 > 65535, i.e. d >= 256 px) are written as invalid: KITTI's format cannot hold them.
void writeKittiPng(const std::string& path, uint32_t width, uint32_t height, std::span<const float> disparity);

// Reads a 16-bit single-channel KITTI PNG: d = value / 256, 0 = invalid.
DisparityMap readKittiPng(const std::string& path);

// Reads any of the above by extension (.pfm or .png). Throws for another extension.
DisparityMap readDisparity(const std::string& path);

// Middlebury 2014 calib.txt. Disparity d and depth Z relate by Z[mm] = baseline * f / (d + doffs).
struct StereoCalib {
    std::array<double, 9> cam0{}; // row-major 3x3 intrinsics of the left camera [f 0 cx; 0 f cy; 0 0 1]
    std::array<double, 9> cam1{}; // the same for the right camera
    double doffs = 0;             // x difference of the principal points, cx1 - cx0, in pixels
    double baselineMm = 0;        // camera baseline in millimetres
    uint32_t width = 0, height = 0;
    uint32_t ndisp = 0; // conservative bound on the number of disparity levels
    bool isint = false;
    double vmin = 0, vmax = 0; // tight bounds on the valid disparities, for colour coding

    double focalPx() const { return cam0[0]; }
    // Planar depth in metres of a disparity in pixels (d > 0).
    double depthMetres(double d) const { return baselineMm * focalPx() / (d + doffs) * 1e-3; }
};

void writeMiddleburyCalib(const std::string& path, const StereoCalib& calib);

// Parses calib.txt: "key=value" lines in any order; unknown keys are ignored (Middlebury files carry dyavg, dymax).
// cam0, cam1, baseline, width, height and ndisp are required; doffs, isint, vmin and vmax default to 0.
StereoCalib readMiddleburyCalib(const std::string& path);

} // namespace sward
