// One frame of the evaluation: its estimate (SGBM on the previews, or another matcher's file) against its ground
// truth, accumulated in total, per class group and per distance band, plus the frame's pictures.
#pragma once

#include "eval/evaluation.h"
#include "eval/splits.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sward {

// What every frame of one dataset is evaluated with.
struct DatasetSetup {
    std::string dir, disparitiesDir, pictureDir;
    const EvaluationOptions* options = nullptr;
    StereoCalib calib;
    std::optional<ResolvedSgbm> sgbm;  // empty: estimates are read from disparitiesDir
    bool semantic = false;             // the dataset has semantic/ images
    bool occlusion = false;            // the dataset has occlusion/ masks: non-occluded metrics too
    double colourLo = 0, colourHi = 1; // disparity colour scale of the pictures
};

// One frame's accumulators, merged into the dataset's in frame order.
struct FrameWork {
    uint32_t frame = 0;
    ErrorAccumulator total;
    std::optional<ErrorAccumulator> nonOccluded; // pixels visible in both views (with occlusion/ masks)
    std::vector<ErrorAccumulator> classes; // per kClassGroups entry; empty without semantic/
    std::vector<ErrorAccumulator> bands;   // per distance band
    double matchSeconds = 0;
};

// Evaluates one frame and writes its pictures (and saved SGBM estimate) when the options ask for them.
FrameWork evaluateFrame(const DatasetSetup& setup, uint32_t frame);

} // namespace sward
