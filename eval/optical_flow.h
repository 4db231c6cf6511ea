// The optical-flow methods sward-eval flow runs as baselines: OpenCV's dense methods of its `video` module, each
// with every parameter fixed and named (docs/evaluation.md, "Optical flow"), or "files": another method's output.
#pragma once

#include "io/flow_files.h"

#include <opencv2/core.hpp>

#include <string>

namespace sward {

enum class FlowMethod {
    DisUltrafast, // cv::DISOpticalFlow, PRESET_ULTRAFAST
    DisFast,      // PRESET_FAST
    DisMedium,    // PRESET_MEDIUM ("dis")
    Farneback,    // cv::FarnebackOpticalFlow with OpenCV's default parameters
    Files,        // another method's flow files (--flow DIR)
};

// Parses "dis" (= dis-medium), "dis-ultrafast", "dis-fast", "dis-medium", "farneback" or "files"; throws
// sward::Error listing the choices otherwise.
FlowMethod parseFlowMethod(const std::string& text);
const char* flowMethodName(FlowMethod method);
// One line naming the method and every parameter it runs with, read back from OpenCV (the report's "Method").
std::string flowMethodDescription(FlowMethod method);

// The forward flow from `first` to `second`, two 8-bit one-channel images of the same size; dense (every vector
// valid). `method` must not be Files. OpenCV runs on the calling thread's setting (eval/frame_batches.h).
FlowField computeFlow(FlowMethod method, const cv::Mat& first, const cv::Mat& second);

} // namespace sward
