// Optical-flow evaluation of a sward dataset (docs/evaluation.md, "Optical flow"): an OpenCV method on consecutive
// tonemapped left previews, or another method's flow files, against the ground-truth forward flow
// (flow_forward/); EPE and KITTI Fl over all pixels with truth and over those visible in both frames, per frame,
// per semantic class group and per distance band, pictures, and a report (eval/flow_report.h).
//
// Results are reproducible: frames run on several threads, OpenCV single-threaded inside each, accumulators merged
// in frame order (eval/frame_batches.h), so every output file is bitwise identical whatever the thread count.
#pragma once

#include "eval/flow_metrics.h"
#include "eval/optical_flow.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sward {

struct FlowEvaluationOptions {
    std::string datasetDir;
    std::string outDir;  // report folder; empty: <datasetDir>/eval-flow
    std::string flowDir; // another method's NNNNNN.flo / NNNNNN.png (method Files); empty: run `method`
    FlowMethod method = FlowMethod::DisMedium;
    std::vector<double> bandEdgesMetres = {5, 10, 20, 50}; // distance bands [0,5) [5,10) ... [50,inf) m
    std::optional<std::pair<uint32_t, uint32_t>> frames;   // [first, last) frame numbers; default: all
    bool pictures = true;                                  // per-frame flow colour and EPE PNGs
    uint32_t threads = 0;                                  // frames evaluated at once; 0: every core
    std::function<void(const std::string&)> log;           // progress lines; may be empty
};

struct FlowFrameMetrics {
    uint32_t frame = 0;
    FlowMetrics all, noc;
};

struct FlowGroup {
    std::string name;                    // class group ("vegetation", ...) or distance band ("5-10 m")
    double minMetres = 0, maxMetres = 0; // distance bands only
    FlowErrors errors;
};

struct FlowEvaluation {
    std::string datasetDir, outDir;
    std::string method; // one line: the method and its parameters, or the folder flow files were read from
    uint32_t width = 0, height = 0;
    bool masks = false; // the dataset has flow_forward_mask/: "noc" figures are meaningful
    std::vector<FlowFrameMetrics> frames;
    FlowErrors total;
    std::vector<FlowGroup> classes; // empty without semantic/
    std::vector<FlowGroup> bands;   // empty without depth/
    double flowSeconds = 0;         // wall-clock time spent in the method (log only, never in a file)
};

// The whole tool: evaluates the dataset and writes the report atomically (all of it or nothing).
FlowEvaluation runFlowEvaluation(const FlowEvaluationOptions& options);

} // namespace sward
