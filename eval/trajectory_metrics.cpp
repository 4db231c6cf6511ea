#include "eval/trajectory_metrics.h"

#include "common/error.h"
#include "common/input_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sward {

namespace {

cv::Vec3d position(const Pose& p) {
    return {p(0, 3), p(1, 3), p(2, 3)};
}

cv::Matx33d rotation(const Pose& p) {
    return p.get_minor<3, 3>(0, 0);
}

Pose makePose(const cv::Matx33d& r, const cv::Vec3d& t) {
    Pose p = Pose::eye();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) p(i, j) = r(i, j);
        p(i, 3) = t[i];
    }
    return p;
}

double rmse(const std::vector<cv::Vec3d>& a, const std::vector<cv::Vec3d>& b, const Pose& align) {
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const cv::Vec3d moved = rotation(align) * a[i] + position(align);
        sum += cv::norm(moved - b[i], cv::NORM_L2SQR);
    }
    return std::sqrt(sum / double(a.size()));
}

// KITTI's sub-sequences of one length: from every frame i to the first j with dist[j] - dist[i] >= length.
RelativeError relativeError(const std::vector<Pose>& truth, const std::vector<Pose>& estimate,
                            const std::vector<double>& dist, double length) {
    RelativeError e;
    e.lengthMetres = length;
    double t = 0, r = 0;
    for (size_t i = 0, j = 0; i < truth.size(); ++i) {
        j = std::max(j, i);
        while (j < truth.size() && dist[j] - dist[i] < length) ++j;
        if (j == truth.size()) break; // later starts travel even less
        const Pose error = relativePose(relativePose(truth[i], truth[j]), relativePose(estimate[i], estimate[j]));
        t += cv::norm(position(error)) / length;
        r += rotationAngleDegrees(error) / length;
        ++e.pairs;
    }
    if (e.pairs > 0) {
        e.translationPercent = 100 * t / e.pairs;
        e.rotationDegPerMetre = r / e.pairs;
    }
    return e;
}

// Why a pose read from a file is not a camera pose ("" when it is): its 3x3 part must be a rotation (the metrics
// invert it as its transpose, so a scaled or sheared matrix would give errors that mean nothing) and its position
// a place (1e308 passes isfinite, then overflows to inf in the first alignment).
std::string poseProblem(const Pose& p) {
    const cv::Matx33d r = rotation(p);
    const double offIdentity = cv::norm(r.t() * r - cv::Matx33d::eye(), cv::NORM_INF);
    char text[160];
    if (!(offIdentity <= kPoseRotationTolerance)) {
        std::snprintf(text, sizeof text, "the 3x3 part is not a rotation (max |R^T R - I| = %.3g, over %g)",
                      offIdentity, kPoseRotationTolerance);
        return text;
    }
    const double det = cv::determinant(r);
    if (!(std::abs(det - 1.0) <= kPoseRotationTolerance)) {
        std::snprintf(text, sizeof text, "the 3x3 part is a reflection, not a rotation (determinant %.6g, not 1)", det);
        return text;
    }
    const cv::Vec3d t = position(p);
    if (!(std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}) <= kMaxPoseTranslationMetres)) {
        std::snprintf(text, sizeof text, "the position (%.3g, %.3g, %.3g) lies beyond %g m of the origin on an axis",
                      t[0], t[1], t[2], kMaxPoseTranslationMetres);
        return text;
    }
    return {};
}

} // namespace

double rotationAngleDegrees(const Pose& pose) {
    const double c = (pose(0, 0) + pose(1, 1) + pose(2, 2) - 1) / 2;
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / CV_PI;
}

Pose inverseRigid(const Pose& pose) {
    const cv::Matx33d rt = rotation(pose).t();
    return makePose(rt, -(rt * position(pose)));
}

Pose relativePose(const Pose& a, const Pose& b) {
    return inverseRigid(a) * b;
}

std::vector<Pose> readKittiPoses(const std::string& path) {
    std::istringstream file(readInputFile(path, "pose file"));
    std::vector<Pose> poses;
    uint32_t lineNumber = 0;
    for (std::string line; std::getline(file, line);) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream in(line);
        std::vector<double> v;
        for (double x; in >> x;) v.push_back(x);
        const bool numbersOnly = in.eof();
        require(numbersOnly && v.size() == 12 &&
                    std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }),
                path + " line " + std::to_string(lineNumber) +
                    ": expected 12 finite numbers (KITTI pose: 3x4 camera-to-world, row-major)");
        Pose p = Pose::eye();
        for (int k = 0; k < 12; ++k) p(k / 4, k % 4) = v[k];
        const std::string problem = poseProblem(p);
        require(problem.empty(), path + " line " + std::to_string(lineNumber) + ": " + problem);
        poses.push_back(p);
    }
    require(!poses.empty(), "pose file '" + path + "' holds no poses");
    return poses;
}

std::string kittiPosesText(const std::vector<Pose>& poses) {
    std::string text;
    char buffer[32];
    for (const Pose& p : poses) {
        for (int k = 0; k < 12; ++k) {
            std::snprintf(buffer, sizeof buffer, "%.17g", p(k / 4, k % 4));
            text += buffer;
            text += k == 11 ? '\n' : ' ';
        }
    }
    return text;
}

Pose umeyamaRigid(const std::vector<cv::Vec3d>& from, const std::vector<cv::Vec3d>& to) {
    require(!from.empty() && from.size() == to.size(), "umeyamaRigid: point sets of different sizes");
    cv::Vec3d mf(0, 0, 0), mt(0, 0, 0);
    for (size_t i = 0; i < from.size(); ++i) {
        mf += from[i];
        mt += to[i];
    }
    mf /= double(from.size());
    mt /= double(to.size());
    cv::Matx33d cov = cv::Matx33d::zeros(); // sum (to - mt)(from - mf)^T
    for (size_t i = 0; i < from.size(); ++i) cov += (to[i] - mt) * (from[i] - mf).t();
    cv::Mat w, u, vt;
    cv::SVD::compute(cv::Mat(cov), w, u, vt);
    cv::Matx33d s = cv::Matx33d::eye();
    // A reflection would fit better than any rotation for degenerate (collinear, planar) paths: forbid it.
    if (cv::determinant(u) * cv::determinant(vt) < 0) s(2, 2) = -1;
    const cv::Matx33d r = cv::Matx33d(u) * s * cv::Matx33d(vt);
    return makePose(r, mt - r * mf);
}

TrajectoryMetrics evaluateTrajectory(const std::vector<Pose>& truth, const std::vector<Pose>& estimate,
                                     const std::vector<double>& lengthsMetres) {
    require(!truth.empty() && truth.size() == estimate.size(), "trajectory of " + std::to_string(estimate.size()) +
                                                                   " poses for " + std::to_string(truth.size()) +
                                                                   " ground-truth frames");
    TrajectoryMetrics m;
    m.frames = uint32_t(truth.size());
    std::vector<double> dist(truth.size(), 0.0);
    std::vector<cv::Vec3d> gt, est;
    const Pose firstAlign = truth[0] * inverseRigid(estimate[0]); // maps the estimate's frame 0 onto the truth's
    for (size_t i = 0; i < truth.size(); ++i) {
        gt.push_back(position(truth[i]));
        est.push_back(position(estimate[i]));
        FramePoseError f;
        f.positionError = cv::norm(position(firstAlign * estimate[i]) - gt[i]);
        if (i > 0) {
            const Pose error =
                relativePose(relativePose(truth[i - 1], truth[i]), relativePose(estimate[i - 1], estimate[i]));
            f.translationMetres = cv::norm(position(error));
            f.rotationDegrees = rotationAngleDegrees(error);
            f.stepMetres = cv::norm(gt[i] - gt[i - 1]);
            dist[i] = dist[i - 1] + f.stepMetres;
        }
        m.perFrame.push_back(f);
    }
    m.pathMetres = dist.back();
    m.ateFirstFrameRmse = rmse(est, gt, firstAlign);
    m.ateUmeyamaRmse = rmse(est, gt, umeyamaRigid(est, gt));
    m.endErrorMetres = m.perFrame.back().positionError;
    double t = 0, r = 0;
    uint32_t pairs = 0;
    for (double length : lengthsMetres) {
        require(length > 0 && std::isfinite(length), "sub-sequence lengths must be positive");
        m.relative.push_back(relativeError(truth, estimate, dist, length));
        const RelativeError& e = m.relative.back();
        if (e.pairs == 0) continue;
        t += e.translationPercent * e.pairs;
        r += e.rotationDegPerMetre * e.pairs;
        pairs += e.pairs;
    }
    if (pairs > 0) {
        m.driftPercent = t / pairs;
        m.rotationDegPerMetre = r / pairs;
    }
    return m;
}

SegmentDrift segmentDrift(const TrajectoryMetrics& metrics, uint32_t first, uint32_t end) {
    SegmentDrift d;
    double t = 0, r = 0;
    // Frame i's error is the motion from i - 1 to i: a segment's own motions start at first + 1.
    for (uint32_t i = first + 1; i < std::min<uint32_t>(end, metrics.frames); ++i) {
        d.distanceMetres += metrics.perFrame[i].stepMetres;
        t += metrics.perFrame[i].translationMetres;
        r += metrics.perFrame[i].rotationDegrees;
    }
    if (d.distanceMetres > 0) {
        d.translationPercent = 100 * t / d.distanceMetres;
        d.rotationDegPerMetre = r / d.distanceMetres;
    }
    return d;
}

} // namespace sward
