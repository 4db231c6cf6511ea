// The odometry report (docs/evaluation.md, "Odometry"): metrics.json, report.md, the estimated and true
// trajectories as KITTI pose files, and PNG plots (trajectory top view, features and inliers per class over the
// frames). Every file is a pure function of the result, so it is bitwise identical whatever the thread count.
#pragma once

#include "eval/odometry.h"

#include <string>

namespace sward {

std::string odometryJson(const OdometryResult& result);
std::string odometryMarkdown(const OdometryResult& result, bool pictures);

// Writes every report file into `dir` (which must exist); the plots only when `pictures`.
void writeOdometryReport(const OdometryResult& result, const std::string& dir, bool pictures);

// The plots (eval/odometry_plots.cpp): trajectory.png, features.png, inliers.png in `dir`.
void writeOdometryPlots(const OdometryResult& result, const std::string& dir);

} // namespace sward
