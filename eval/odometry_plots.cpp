// The odometry report's plots (eval/odometry_report.h), drawn with OpenCV on white canvases.
#include "eval/number_format.h"
#include "eval/odometry_report.h"
#include "eval/pictures.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

constexpr int kW = 760, kH = 420, kLeft = 70, kRight = 170, kTop = 40, kBottom = 50;
const cv::Scalar kBlack(0, 0, 0), kGrey(210, 210, 210);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// BGR colour of each feature class in the plots.
const cv::Scalar kClassColours[kFeatureClasses] = {{40, 90, 140}, {60, 140, 60},  {0, 0, 200},    {0, 180, 0},
                                                   {200, 80, 0},  {230, 170, 90}, {128, 128, 128}};

// Maps data coordinates [x0, x1] x [y0, y1] to the plot area.
struct Axes {
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    int right = kW - kRight, bottom = kH - kBottom;
    cv::Point at(double x, double y) const {
        return {kLeft + int(std::lround((x - x0) / (x1 - x0) * (right - kLeft))),
                bottom - int(std::lround((y - y0) / (y1 - y0) * (bottom - kTop)))};
    }
};

void drawFrame(cv::Mat& canvas, const Axes& a, const std::string& title, const std::string& xLabel, int decimals) {
    for (int k = 0; k <= 4; ++k) {
        const double x = a.x0 + (a.x1 - a.x0) * k / 4, y = a.y0 + (a.y1 - a.y0) * k / 4;
        cv::line(canvas, a.at(x, a.y0), a.at(x, a.y1), kGrey, 1);
        cv::line(canvas, a.at(a.x0, y), a.at(a.x1, y), kGrey, 1);
        cv::putText(canvas, fixed(x, decimals), a.at(x, a.y0) + cv::Point(-12, 18), kFont, 0.4, kBlack, 1, cv::LINE_AA);
        cv::putText(canvas, fixed(y, decimals), a.at(a.x0, y) + cv::Point(-64, 4), kFont, 0.4, kBlack, 1, cv::LINE_AA);
    }
    cv::rectangle(canvas, a.at(a.x0, a.y1), a.at(a.x1, a.y0), kBlack, 1);
    cv::putText(canvas, title, {kLeft, 24}, kFont, 0.5, kBlack, 1, cv::LINE_AA);
    cv::putText(canvas, xLabel, {kLeft + 200, kH - 12}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
}

void legend(cv::Mat& canvas, int index, const std::string& label, const cv::Scalar& colour) {
    const int x = kW - kRight + 12, y = kTop + 14 + 18 * index;
    cv::line(canvas, {x, y - 4}, {x + 22, y - 4}, colour, 2);
    cv::putText(canvas, label, {x + 28, y}, kFont, 0.4, kBlack, 1, cv::LINE_AA);
}

// Counts of every class with any count, over the frames, one curve each.
void plotCounts(const OdometryResult& r, ClassCounts FrameOdometry::*count, const std::string& title,
                const std::string& path) {
    Axes a;
    a.x0 = r.frameNumbers.front();
    a.x1 = std::max<double>(r.frameNumbers.back(), a.x0 + 1);
    double yMax = 1;
    for (const FrameOdometry& f : r.frames)
        for (uint64_t v : f.*count) yMax = std::max(yMax, double(v));
    a.y1 = yMax * 1.05;
    cv::Mat canvas(kH, kW, CV_8UC3, cv::Scalar(255, 255, 255));
    drawFrame(canvas, a, title, "frame", 0);
    int index = 0;
    for (size_t c = 0; c < kFeatureClasses; ++c) {
        std::vector<cv::Point> points;
        uint64_t any = 0;
        for (const FrameOdometry& f : r.frames) {
            points.push_back(a.at(f.frame, double((f.*count)[c])));
            any += (f.*count)[c];
        }
        if (any == 0) continue;
        cv::polylines(canvas, points, false, kClassColours[c], 2, cv::LINE_AA);
        legend(canvas, index++, kFeatureClassNames[c], kClassColours[c]);
    }
    // Failed frames: a red tick on the frame axis.
    for (const FrameOdometry& f : r.frames)
        if (f.failed) cv::line(canvas, a.at(f.frame, a.y0), a.at(f.frame, a.y0) + cv::Point(0, -10), {0, 0, 255}, 2);
    writePng(path, canvas);
}

// Top view (world x right, y up) of both trajectories at one scale, the start marked.
void plotTrajectory(const OdometryResult& r, const std::string& path) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const auto* poses : {&r.truth, &r.estimate})
        for (const Pose& p : *poses) {
            x0 = std::min(x0, p(0, 3)), x1 = std::max(x1, p(0, 3));
            y0 = std::min(y0, p(1, 3)), y1 = std::max(y1, p(1, 3));
        }
    // Equal scale on both axes: widen the narrower range around its centre to the plot area's aspect ratio.
    const double aspect = double(kW - kLeft - kRight) / double(kH - kTop - kBottom);
    const double span = std::max({(x1 - x0) / aspect, y1 - y0, 1.0}) * 1.1;
    Axes a;
    a.x0 = (x0 + x1) / 2 - span * aspect / 2, a.x1 = a.x0 + span * aspect;
    a.y0 = (y0 + y1) / 2 - span / 2, a.y1 = a.y0 + span;
    cv::Mat canvas(kH, kW, CV_8UC3, cv::Scalar(255, 255, 255));
    drawFrame(canvas, a, "trajectory, top view (world metres; y axis: world y)", "world x (m)", 1);
    const std::pair<const std::vector<Pose>*, cv::Scalar> curves[] = {{&r.truth, {0, 0, 0}},
                                                                      {&r.estimate, {0, 0, 220}}};
    for (const auto& [poses, colour] : curves) {
        std::vector<cv::Point> points;
        for (const Pose& p : *poses) points.push_back(a.at(p(0, 3), p(1, 3)));
        cv::polylines(canvas, points, false, colour, 2, cv::LINE_AA);
    }
    cv::circle(canvas, a.at(r.truth[0](0, 3), r.truth[0](1, 3)), 5, {0, 160, 0}, 2, cv::LINE_AA);
    legend(canvas, 0, "ground truth", {0, 0, 0});
    legend(canvas, 1, "estimate", {0, 0, 220});
    legend(canvas, 2, "start (circle)", {0, 160, 0});
    writePng(path, canvas);
}

} // namespace

void writeOdometryPlots(const OdometryResult& result, const std::string& dir) {
    plotTrajectory(result, dir + "/trajectory.png");
    if (result.frames.empty()) return;
    plotCounts(result, &FrameOdometry::keypoints, "left keypoints per class (red ticks: failed frames)",
               dir + "/features.png");
    plotCounts(result, &FrameOdometry::inliers, "RANSAC inliers per class of the previous frame's keypoint",
               dir + "/inliers.png");
}

} // namespace sward
