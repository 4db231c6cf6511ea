// The evaluation's pictures: colour-coded disparity maps, 8-bit signed difference images and error-histogram
// plots, written as PNG through OpenCV (BGR).
#pragma once

#include "eval/stereo_metrics.h"

#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Encodes `image` as PNG and writes it atomically; throws sward::Error naming `path`.
void writePng(const std::string& path, const cv::Mat& image);

// Turbo colour map of `d` over [lo, hi]; black where the disparity is invalid.
cv::Mat colourDisparity(const std::vector<float>& d, uint32_t width, uint32_t height, double lo, double hi);

// The paper's signed difference image (signedDifference8 of estimate - truth); 0 where either is invalid.
cv::Mat differenceImage(const std::vector<float>& estimate, const std::vector<float>& truth, uint32_t width,
                        uint32_t height);

// One curve of an error-histogram plot.
struct Curve {
    std::string label;
    cv::Scalar colour; // BGR
    const ErrorAccumulator* accumulator;
};

// Line plot of signed-error histograms (fraction of estimated pixels per pixel of error), one curve per input.
void plotHistograms(const std::string& path, const std::string& title, const std::vector<Curve>& curves);

} // namespace sward
