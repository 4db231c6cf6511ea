#include "eval/flow_metrics.h"

#include "common/error.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace sward {

void FlowAccumulator::add(float estU, float estV, float truthU, float truthV) {
    assert(isValidFlow(truthU, truthV));
    ++gtPixels_;
    // In double, differences and squares of floats are exact enough that thresholds decide on the true error,
    // and std::sqrt is correctly rounded: the same value on every machine.
    const double truth = std::sqrt(double(truthU) * truthU + double(truthV) * truthV);
    sumTruth_ += truth;
    if (!isValidFlow(estU, estV)) return;
    ++estimated_;
    const double du = double(estU) - double(truthU), dv = double(estV) - double(truthV);
    const double squared = du * du + dv * dv;
    const double epe = std::sqrt(squared);
    sumEpe_ += epe;
    sumSquares_ += squared;
    maxEpe_ = std::max(maxEpe_, epe);
    for (size_t i = 0; i < kFlowBadThresholds.size(); ++i) bad_[i] += epe > kFlowBadThresholds[i];
    fl_ += isFlOutlier(epe, truth);
}

void FlowAccumulator::merge(const FlowAccumulator& other) {
    gtPixels_ += other.gtPixels_;
    estimated_ += other.estimated_;
    fl_ += other.fl_;
    for (size_t i = 0; i < bad_.size(); ++i) bad_[i] += other.bad_[i];
    sumEpe_ += other.sumEpe_;
    sumSquares_ += other.sumSquares_;
    sumTruth_ += other.sumTruth_;
    maxEpe_ = std::max(maxEpe_, other.maxEpe_);
}

FlowMetrics FlowAccumulator::metrics() const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    FlowMetrics m;
    m.gtPixels = gtPixels_;
    m.estimatedPixels = estimated_;
    m.coverage = gtPixels_ ? double(estimated_) / double(gtPixels_) : nan;
    m.meanTruthMagnitude = gtPixels_ ? sumTruth_ / double(gtPixels_) : nan;
    if (estimated_ == 0) {
        m.epe = m.rmsEpe = m.maxEpe = m.fl = nan;
        m.bad.fill(nan);
        return m;
    }
    const double n = double(estimated_);
    m.epe = sumEpe_ / n;
    m.rmsEpe = std::sqrt(sumSquares_ / n);
    m.maxEpe = maxEpe_;
    for (size_t i = 0; i < bad_.size(); ++i) m.bad[i] = double(bad_[i]) / n;
    m.fl = double(fl_) / n;
    return m;
}

FlowMetrics computeFlowMetrics(const FlowField& estimate, const FlowField& truth) {
    require(estimate.width == truth.width && estimate.height == truth.height && estimate.uv.size() == truth.uv.size(),
            "flow estimate " + std::to_string(estimate.width) + "x" + std::to_string(estimate.height) +
                " and ground truth " + std::to_string(truth.width) + "x" + std::to_string(truth.height) +
                " differ in size");
    FlowAccumulator accumulator;
    for (size_t i = 0; i < truth.uv.size() / 2; ++i)
        if (isValidFlow(truth.u(i), truth.v(i))) accumulator.add(estimate.u(i), estimate.v(i), truth.u(i), truth.v(i));
    return accumulator.metrics();
}

} // namespace sward
