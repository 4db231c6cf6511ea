// Stereo evaluation of a sward dataset (docs/evaluation.md): OpenCV StereoSGBM on the tonemapped left/right
// previews, or another matcher's disparity files, compared with the ground-truth disparity; metrics per frame,
// per semantic class and distance band, pictures, and a report (metrics.json, metrics.csv, report.md).
// The steps have a file each: dataset_reader (the dataset's files), sgbm (the matcher), frame_evaluation (one
// frame), pictures (PNGs), report (the report files); this file runs them over the frames.
//
// Results are reproducible: frames may be matched on several threads, but OpenCV runs single-threaded inside
// each and accumulators are merged in frame order, so every output file is bitwise identical whatever the thread
// count. Timings go to the log only, never into a file.
#pragma once

#include "eval/sgbm.h"
#include "eval/stereo_metrics.h"
#include "io/disparity_files.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sward {

struct EvaluationOptions {
    std::string datasetDir;
    std::string outDir;         // report folder; empty: <datasetDir>/eval
    std::string disparitiesDir; // another matcher's NNNNNN.pfm / NNNNNN.png; empty: run SGBM
    std::string againstDir;     // optional second dataset, evaluated with the same settings
    std::string againstDisparitiesDir;
    SgbmOptions sgbm;
    std::vector<double> bandEdgesMetres = {5, 10, 20, 50}; // distance bands [0,5) [5,10) ... [50,inf) m
    std::optional<std::pair<uint32_t, uint32_t>> frames;   // [first, last) frame numbers; default: all
    bool pictures = true;                                  // per-frame colour-coded disparity and difference PNGs
    bool saveDisparities = false;                          // write the SGBM estimates to <outDir>/disparity/NNNNNN.pfm
    unsigned threads = 0;                                  // frames matched at once; 0: hardware concurrency
    std::function<void(const std::string&)> log;           // progress lines; may be empty
};

struct FrameMetrics {
    uint32_t frame = 0;
    StereoMetrics metrics;
};

struct GroupMetrics {
    std::string name; // semantic class ("vegetation", "ground", "object", "other") or band label ("5-10 m")
    double minMetres = 0, maxMetres = 0; // distance bands only
    ErrorAccumulator accumulator;
};

struct DatasetEvaluation {
    std::string datasetDir;
    std::string matcher; // one line: SGBM settings, or the folder disparities were read from
    std::optional<ResolvedSgbm> sgbm;
    StereoCalib calib;
    uint32_t width = 0, height = 0;
    std::vector<FrameMetrics> frames;
    ErrorAccumulator total;                      // every pixel with ground truth ("all")
    std::optional<ErrorAccumulator> nonOccluded; // those visible in both views ("noc"); without occlusion/: none
    std::vector<GroupMetrics> classes; // empty when the dataset has no semantic/ folder
    std::vector<GroupMetrics> bands;
    double matchSeconds = 0; // wall-clock time spent in SGBM (log only)
};

struct EvaluationReport {
    DatasetEvaluation main;
    std::optional<DatasetEvaluation> against;
    std::string outDir;
};

// Evaluates one dataset; writes per-frame pictures (and saved disparities) under `pictureDir` when asked.
DatasetEvaluation evaluateDataset(const std::string& datasetDir, const std::string& disparitiesDir,
                                  const EvaluationOptions& options, const std::string& pictureDir);

// The whole tool: evaluates the dataset (and the --against dataset) and writes the report.
EvaluationReport runEvaluation(const EvaluationOptions& options);

} // namespace sward
