// `sward-eval look`: the realism instrument (docs/evaluation.md, "Realism statistics"). Statistics of colour,
// gradients, Laplacian pyramid, spectrum, keypoints and texture (eval/look_statistics.h) of every frame's 8-bit
// preview, per region of its semantic image (eval/look_regions.h), and with a reference folder the same of real
// photographs and, per statistic, the gap between the two in units of the real images' spread.
//
// Results are reproducible: frames run in parallel, OpenCV single-threaded inside each, results kept in frame
// order, so every output file is bitwise identical whatever the thread count.
#pragma once

#include "eval/look_statistics.h"

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sward {

struct LookOptions {
    std::string datasetDir;
    std::string referenceDir;                            // real photographs; empty: none
    std::string outDir;                                  // report folder; empty: <datasetDir>/eval-look
    std::optional<std::pair<uint32_t, uint32_t>> frames; // [first, end) frame numbers; default: all
    unsigned threads = 0;                                // images processed at once; 0: every core
    bool pictures = true;                                // the PNG plots
    std::function<void(const std::string&)> log;         // progress lines; may be empty
};

// The statistics of one image's regions, in region order.
struct LookImageResult {
    std::string name; // the frame name "000042" or the reference file name
    uint32_t width = 0, height = 0;
    std::vector<std::pair<std::string, LookStatistics>> regions;
    // Sward frames: the turf pixels failing the sharp-texture test, as a share of the non-sky pixels (NaN without
    // any non-sky pixel).
    double smoothTurfShare = NAN;
};

// One statistic as the reports name it, and whether it is compared with the real images (counts are not).
struct LookField {
    const char* key;
    double value;
    bool compared;
};
std::vector<LookField> lookFields(const LookStatistics& s);

// Per region: the median of each field over the images holding the region (NaN fields left out), the quartiles
// and std behind the gap, and how many images hold the region.
struct LookSummary {
    uint32_t images = 0;
    std::vector<std::string> keys;
    std::vector<double> median, q1, q3, std;
};
using LookSummaries = std::map<std::string, LookSummary>; // by region name

struct LookResult {
    std::string datasetDir, referenceDir;
    std::vector<LookImageResult> frames, reference;
    std::vector<std::string> regionOrder; // sward's regions, then any other reference region, first seen first
    LookSummaries sward, real;
    double smoothTurfShare = NAN; // median over the frames
};

// The summary of `images`, per region name.
LookSummaries summarise(const std::vector<LookImageResult>& images);
// (sward median - real median) / (real IQR, or the real std when the IQR is 0); NaN when either is missing or the
// spread is 0.
double lookGap(const LookSummary& sward, const LookSummary& real, size_t field);

// Measures every chosen frame (and the reference images); writes nothing.
LookResult evaluateLook(const LookOptions& options);

// The whole tool: evaluates and writes the report folder atomically.
LookResult runLook(const LookOptions& options);

} // namespace sward
