// Stereo evaluation of a sward dataset (docs/evaluation.md): OpenCV StereoSGBM on the tonemapped left/right
// previews, or another matcher's disparity files, compared with the ground-truth disparity; metrics per frame,
// per semantic class and distance band, pictures, and a report (metrics.json, metrics.csv, report.md).
//
// Results are reproducible: frames may be matched on several threads, but OpenCV runs single-threaded inside
// each and accumulators are merged in frame order, so every output file is bitwise identical whatever the thread
// count. Timings go to the log only, never into a file.
#pragma once

#include "io/disparity_files.h"
#include "eval/stereo_metrics.h"

#include <cstdint>
#include <functional>
#include <optional>
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
    ErrorAccumulator total;
    std::vector<GroupMetrics> classes; // empty when the dataset has no semantic/ folder
    std::vector<GroupMetrics> bands;
    double matchSeconds = 0; // wall-clock time spent in SGBM (log only)
};

struct EvaluationReport {
    DatasetEvaluation main;
    std::optional<DatasetEvaluation> against;
    std::string outDir;
};

// Frame numbers of a dataset: every 6-digit NNNNNN.{pfm,exr,png} in <dir>/disparity, sorted.
std::vector<uint32_t> listDatasetFrames(const std::string& dir);

// Ground-truth disparity of one frame: disparity/NNNNNN.pfm, else .exr, else the KITTI .png (lossy).
DisparityMap readGroundTruth(const std::string& dir, uint32_t frame);

// SGBM on two 8-bit images (1 or 3 channels, interleaved, top row first) of the same size. Returns the left
// view's disparity in pixels, 0 where SGBM gives none. `resolved` must come from resolveSgbm.
std::vector<float> runSgbm(const ResolvedSgbm& resolved, uint32_t width, uint32_t height, std::span<const uint8_t> left,
                           std::span<const uint8_t> right);
ResolvedSgbm resolveSgbm(const SgbmOptions& options, const StereoCalib& calib, uint32_t width);

// Evaluates one dataset; writes per-frame pictures (and saved disparities) under `pictureDir` when asked.
DatasetEvaluation evaluateDataset(const std::string& datasetDir, const std::string& disparitiesDir,
                                  const EvaluationOptions& options, const std::string& pictureDir);

// The whole tool: evaluates the dataset (and the --against dataset) and writes the report.
EvaluationReport runEvaluation(const EvaluationOptions& options);

// Report writers, exposed for tests.
std::string metricsJson(const EvaluationReport& report);
std::string metricsCsv(const EvaluationReport& report);
std::string reportMarkdown(const EvaluationReport& report);

} // namespace sward
