// The stereo matcher sward-eval runs by default: OpenCV's StereoSGBM with every parameter named and resolved
// against the dataset's calib.txt (docs/evaluation.md).
#pragma once

#include "io/disparity_files.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sward {

enum class SgbmMode { Sgbm, HH, ThreeWay, HH4 };

// Parses "sgbm", "hh", "3way" or "hh4"; throws sward::Error otherwise.
SgbmMode parseSgbmMode(const std::string& text);
const char* sgbmModeName(SgbmMode mode);

struct SgbmOptions {
    SgbmMode mode = SgbmMode::Sgbm;
    int blockSize = 7;                 // odd, 1..31
    std::optional<int> numDisparities; // default: calib.txt ndisp rounded up to a multiple of 16
    std::optional<int> p1, p2;         // defaults 8*cn*blockSize^2 and 32*cn*blockSize^2 (cn: image channels)
    int uniquenessRatio = 10;          // percent
    int speckleWindowSize = 100;       // pixels; 0 disables speckle filtering
    int speckleRange = 2;              // disparity levels (OpenCV multiplies by 16 internally)
    int disp12MaxDiff = 1;             // left-right check tolerance in pixels; negative disables it
    bool gray = false;                 // match grey images (cn = 1) instead of colour (cn = 3)
};

// The SGBM parameters actually used for one dataset, after defaults are resolved.
struct ResolvedSgbm {
    SgbmOptions options;
    int channels = 3;
    int numDisparities = 0, p1 = 0, p2 = 0;
};

// Resolves the defaults for a dataset of `calib` and image `width`; throws sward::Error for invalid settings.
ResolvedSgbm resolveSgbm(const SgbmOptions& options, const StereoCalib& calib, uint32_t width);

// One line naming every resolved parameter, for the report's "Matcher".
std::string sgbmDescription(const ResolvedSgbm& resolved);

// SGBM on two 8-bit images (1 or 3 channels, interleaved, top row first) of the same size. Returns the left
// view's disparity in pixels, 0 where SGBM gives none. `resolved` must come from resolveSgbm.
std::vector<float> runSgbm(const ResolvedSgbm& resolved, uint32_t width, uint32_t height, std::span<const uint8_t> left,
                           std::span<const uint8_t> right);

} // namespace sward
