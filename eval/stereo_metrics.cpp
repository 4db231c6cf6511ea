#include "eval/stereo_metrics.h"

#include "io/disparity_files.h"
#include "common/error.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace sward {

namespace {

constexpr size_t kAbsBins = size_t(ErrorAccumulator::kAbsRange * ErrorAccumulator::kAbsBinsPerPixel) + 1;
constexpr size_t kSignedBins = size_t(2 * ErrorAccumulator::kSignedRange * ErrorAccumulator::kSignedBinsPerPixel);

// Population standard deviation from sums; clamped because rounding can make the variance slightly negative.
double standardDeviation(double sum, double sumSquares, double n) {
    double mean = sum / n;
    return std::sqrt(std::max(0.0, sumSquares / n - mean * mean));
}

} // namespace

uint8_t signedDifference8(double error) {
    double v = std::round(error) + 127.0; // std::round: halves away from zero, the same on every machine
    return uint8_t(std::clamp(v, 0.0, 255.0));
}

void ErrorAccumulator::add(float estimate, float truth) {
    assert(isValidDisparity(truth));
    ++gtPixels_;
    if (!isValidDisparity(estimate)) return;
    if (absHistogram_.empty()) {
        absHistogram_.assign(kAbsBins, 0);
        signedHistogram_.assign(kSignedBins, 0);
    }
    ++estimated_;
    // In double, the difference of two floats is exact, so thresholds are decided on the true error.
    const double e = double(estimate) - double(truth);
    const double a = std::abs(e);
    sum_ += e;
    sumAbs_ += a;
    sumSquares_ += e * e;
    maxAbs_ = std::max(maxAbs_, a);
    for (size_t i = 0; i < kBadThresholds.size(); ++i) bad_[i] += a > kBadThresholds[i];
    d1_ += isD1Outlier(a, truth);
    const double d8 = double(signedDifference8(e));
    sum8_ += d8;
    sumSquares8_ += d8 * d8;
    absHistogram_[size_t(std::min(a * kAbsBinsPerPixel, double(kAbsBins - 1)))] += 1;
    const double s = std::floor((e + kSignedRange) * kSignedBinsPerPixel);
    signedHistogram_[size_t(std::clamp(s, 0.0, double(kSignedBins - 1)))] += 1;
}

void ErrorAccumulator::addMaps(std::span<const float> estimate, std::span<const float> truth) {
    require(estimate.size() == truth.size(), "estimate and ground truth differ in size (" +
                                                 std::to_string(estimate.size()) + " vs " +
                                                 std::to_string(truth.size()) + " pixels)");
    for (size_t i = 0; i < truth.size(); ++i)
        if (isValidDisparity(truth[i])) add(estimate[i], truth[i]);
}

void ErrorAccumulator::merge(const ErrorAccumulator& other) {
    gtPixels_ += other.gtPixels_;
    estimated_ += other.estimated_;
    d1_ += other.d1_;
    for (size_t i = 0; i < bad_.size(); ++i) bad_[i] += other.bad_[i];
    sumAbs_ += other.sumAbs_;
    sum_ += other.sum_;
    sumSquares_ += other.sumSquares_;
    sum8_ += other.sum8_;
    sumSquares8_ += other.sumSquares8_;
    maxAbs_ = std::max(maxAbs_, other.maxAbs_);
    if (other.absHistogram_.empty()) return;
    if (absHistogram_.empty()) {
        absHistogram_ = other.absHistogram_;
        signedHistogram_ = other.signedHistogram_;
        return;
    }
    for (size_t i = 0; i < absHistogram_.size(); ++i) absHistogram_[i] += other.absHistogram_[i];
    for (size_t i = 0; i < signedHistogram_.size(); ++i) signedHistogram_[i] += other.signedHistogram_[i];
}

StereoMetrics ErrorAccumulator::metrics() const {
    StereoMetrics m;
    m.gtPixels = gtPixels_;
    m.estimatedPixels = estimated_;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.coverage = gtPixels_ ? double(estimated_) / double(gtPixels_) : nan;
    if (estimated_ == 0) {
        m.meanAbsError = m.meanError = m.stdError = m.rms = m.maxAbsError = m.d1 = m.stdError8bit = nan;
        m.bad.fill(nan);
        m.accuracy.fill(nan);
        return m;
    }
    const double n = double(estimated_);
    m.meanAbsError = sumAbs_ / n;
    m.meanError = sum_ / n;
    m.stdError = standardDeviation(sum_, sumSquares_, n);
    m.rms = std::sqrt(sumSquares_ / n);
    m.maxAbsError = maxAbs_;
    for (size_t i = 0; i < bad_.size(); ++i) m.bad[i] = double(bad_[i]) / n;
    m.d1 = double(d1_) / n;
    m.stdError8bit = standardDeviation(sum8_, sumSquares8_, n);
    // A_q: the smallest bin whose cumulative count reaches q * n; reported as the bin's lower edge. The overflow
    // bin reports the largest error seen.
    for (size_t q = 0; q < kAccuracyQuantiles.size(); ++q) {
        const uint64_t need = uint64_t(std::ceil(kAccuracyQuantiles[q] * n));
        uint64_t cumulative = 0;
        for (size_t bin = 0; bin < absHistogram_.size(); ++bin) {
            cumulative += absHistogram_[bin];
            if (cumulative >= need) {
                m.accuracy[q] = bin + 1 == absHistogram_.size() ? maxAbs_ : double(bin) / kAbsBinsPerPixel;
                break;
            }
        }
    }
    return m;
}

StereoMetrics computeMetrics(std::span<const float> estimate, std::span<const float> truth) {
    ErrorAccumulator accumulator;
    accumulator.addMaps(estimate, truth);
    return accumulator.metrics();
}

} // namespace sward
