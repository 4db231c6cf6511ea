// Stereo error metrics (Middlebury 2014 / ETH3D / KITTI 2015), pure arithmetic on disparity values.
//
// For every pixel with valid ground truth (isValidDisparity(gt)) the signed error is e = est - gt in pixels.
// Pixels whose estimate is invalid (0, negative or non-finite: the matcher gave no value) do not enter any error
// statistic; they only lower `coverage`. Error statistics are therefore "over estimated pixels", as ETH3D
// reports them next to coverage. docs/evaluation.md defines every field.
//
// Accumulators merge exactly (integer counts, histograms, and double sums added in a fixed order), so a dataset's
// metrics are pooled over all pixels of all frames, never an average of per-frame figures.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace sward {

inline constexpr std::array<double, 4> kBadThresholds = {0.5, 1.0, 2.0, 4.0};       // bad-x: |e| > x px
inline constexpr std::array<double, 4> kAccuracyQuantiles = {0.5, 0.9, 0.95, 0.99}; // A50, A90, A95, A99

// KITTI 2015's D1 outlier: |e| > 3 px AND |e| > 5 % of the true disparity.
inline bool isD1Outlier(double absError, double truth) {
    return absError > 3.0 && absError > 0.05 * truth;
}

// The paper's 8-bit signed difference image: round(e) + 127, clamped to 0..255.
uint8_t signedDifference8(double error);

struct StereoMetrics {
    uint64_t gtPixels = 0;        // pixels with valid ground truth
    uint64_t estimatedPixels = 0; // of those, pixels with a valid estimate
    double coverage = 0;          // estimatedPixels / gtPixels
    // Over estimated pixels (NaN when there are none):
    double meanAbsError = 0, meanError = 0, stdError = 0, rms = 0, maxAbsError = 0;
    std::array<double, 4> bad{};      // fraction with |e| > kBadThresholds[i]
    std::array<double, 4> accuracy{}; // kAccuracyQuantiles of |e|, rounded down to 1/256 px
    double d1 = 0;                    // fraction of KITTI D1 outliers
    double stdError8bit = 0;          // standard deviation of signedDifference8(e), the paper's measure
};

class ErrorAccumulator {
public:
    // |e| histogram: 1/256 px bins (KITTI's disparity resolution) up to kAbsRange px, then one overflow bin.
    static constexpr double kAbsBinsPerPixel = 256.0;
    static constexpr double kAbsRange = 256.0;
    // Signed error histogram for plots: 1/8 px bins over [-kSignedRange, kSignedRange), clamped at the ends.
    static constexpr double kSignedBinsPerPixel = 8.0;
    static constexpr double kSignedRange = 256.0;

    // One pixel whose ground truth is valid (precondition, asserted). An invalid estimate only counts for coverage.
    void add(float estimate, float truth);
    // All pixels of two maps of equal size; pixels without valid ground truth are skipped.
    void addMaps(std::span<const float> estimate, std::span<const float> truth);
    void merge(const ErrorAccumulator& other);

    StereoMetrics metrics() const;
    uint64_t gtPixels() const { return gtPixels_; }
    uint64_t estimatedPixels() const { return estimated_; }
    // Counts per signed-error bin; bin i covers [-kSignedRange + i / kSignedBinsPerPixel, ...). Empty if no pixel.
    const std::vector<uint64_t>& signedHistogram() const { return signedHistogram_; }
    static double signedBinLow(size_t bin) { return -kSignedRange + double(bin) / kSignedBinsPerPixel; }

private:
    uint64_t gtPixels_ = 0, estimated_ = 0, d1_ = 0;
    std::array<uint64_t, 4> bad_{};
    double sumAbs_ = 0, sum_ = 0, sumSquares_ = 0, maxAbs_ = 0;
    double sum8_ = 0, sumSquares8_ = 0;
    std::vector<uint64_t> absHistogram_, signedHistogram_; // allocated on the first estimated pixel
};

// Convenience: metrics of one estimate against one ground truth map (same size, top row first).
StereoMetrics computeMetrics(std::span<const float> estimate, std::span<const float> truth);

} // namespace sward
