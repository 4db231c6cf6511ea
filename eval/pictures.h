// The evaluations' pictures: colour-coded disparity and flow fields, error maps, 8-bit signed difference images and
// error-histogram plots, written as PNG through OpenCV (BGR).
#pragma once

#include "eval/stereo_metrics.h"
#include "io/flow_files.h"

#include <opencv2/core.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

// Encodes `image` as PNG and writes it atomically; throws sward::Error naming `path`.
void writePng(const std::string& path, const cv::Mat& image);

// Turbo colour map of `values` over [lo, hi] (clamped); black where valid(value) is false.
cv::Mat colourValues(std::span<const float> values, uint32_t width, uint32_t height, double lo, double hi,
                     bool (*valid)(float));

// Turbo colour map of `d` over [lo, hi]; black where the disparity is invalid.
cv::Mat colourDisparity(const std::vector<float>& d, uint32_t width, uint32_t height, double lo, double hi);

// The paper's signed difference image (signedDifference8 of estimate - truth); 0 where either is invalid.
cv::Mat differenceImage(const std::vector<float>& estimate, const std::vector<float>& truth, uint32_t width,
                        uint32_t height);

// Middlebury's flow colour coding: hue = direction, saturation = magnitude / maxMagnitude (vectors beyond it are
// darkened); black where the flow is invalid.
cv::Mat colourFlow(const FlowField& flow, double maxMagnitude);

// One curve of an error-histogram plot.
struct Curve {
    std::string label;
    cv::Scalar colour; // BGR
    const ErrorAccumulator* accumulator;
};

// Line plot of signed-error histograms (fraction of estimated pixels per pixel of error), one curve per input.
void plotHistograms(const std::string& path, const std::string& title, const std::vector<Curve>& curves);

} // namespace sward
