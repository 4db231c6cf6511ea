// Optical-flow error metrics (Middlebury / Sintel end-point error, KITTI 2015 Fl), pure arithmetic on flow vectors.
//
// For every pixel with valid ground truth the end-point error is EPE = |estimate - truth| (Euclidean, pixels).
// Pixels whose estimate is invalid (io/flow_files.h: NaN, the method gave no value) enter no error statistic; they
// only lower `coverage`, as in the stereo metrics (eval/stereo_metrics.h). docs/evaluation.md defines every field.
//
// Accumulators merge exactly (integer counts and double sums added in the caller's fixed order), so a dataset's
// metrics are pooled over all pixels of all frames, never an average of per-frame figures.
#pragma once

#include "io/flow_files.h"

#include <array>
#include <cstdint>

namespace sward {

inline constexpr std::array<double, 2> kFlowBadThresholds = {1.0, 3.0}; // bad-x: EPE > x px

// KITTI 2015's Fl outlier: EPE > 3 px AND EPE > 5 % of the true flow's magnitude.
inline bool isFlOutlier(double epe, double truthMagnitude) {
    return epe > 3.0 && epe > 0.05 * truthMagnitude;
}

struct FlowMetrics {
    uint64_t gtPixels = 0;         // pixels with valid ground truth
    uint64_t estimatedPixels = 0;  // of those, pixels with a valid estimate
    double coverage = 0;           // estimatedPixels / gtPixels
    double meanTruthMagnitude = 0; // mean |truth| over gtPixels: how far the scene moved
    // Over estimated pixels (NaN when there are none):
    double epe = 0, rmsEpe = 0, maxEpe = 0;
    std::array<double, 2> bad{}; // fraction with EPE > kFlowBadThresholds[i]
    double fl = 0;               // fraction of KITTI Fl outliers
};

class FlowAccumulator {
public:
    // One pixel whose ground truth is valid (precondition, asserted); an invalid estimate only counts for coverage.
    void add(float estU, float estV, float truthU, float truthV);
    void merge(const FlowAccumulator& other);
    FlowMetrics metrics() const;
    uint64_t gtPixels() const { return gtPixels_; }

private:
    uint64_t gtPixels_ = 0, estimated_ = 0, fl_ = 0;
    std::array<uint64_t, 2> bad_{};
    double sumEpe_ = 0, sumSquares_ = 0, maxEpe_ = 0, sumTruth_ = 0;
};

// Every pixel with truth ("all", KITTI's flow_occ) and those visible in both frames ("noc", mask 255).
struct FlowErrors {
    FlowAccumulator all, noc;
    void add(float estU, float estV, float truthU, float truthV, bool visible) {
        all.add(estU, estV, truthU, truthV);
        if (visible) noc.add(estU, estV, truthU, truthV);
    }
    void merge(const FlowErrors& other) {
        all.merge(other.all);
        noc.merge(other.noc);
    }
};

// Convenience: metrics of one estimate against one truth of the same size over every pixel with valid truth.
FlowMetrics computeFlowMetrics(const FlowField& estimate, const FlowField& truth);

} // namespace sward
