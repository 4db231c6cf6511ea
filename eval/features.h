// Feature detection and matching for the odometry evaluation (docs/evaluation.md, "Odometry"): OpenCV's ORB,
// AKAZE and SIFT with fixed parameters, a deterministic keypoint order, the ratio-test matcher, the stereo matcher
// of a rectified pair (same row, positive disparity), and the semantic class of a keypoint's pixel.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sward {

enum class Detector { Orb, Akaze, Sift };

// "orb", "akaze", "sift"; throws sward::Error naming the value otherwise.
Detector parseDetector(const std::string& name);
const char* detectorName(Detector detector);
// One line with every fixed parameter, for the report.
std::string detectorDescription(Detector detector);

// The feature classes a keypoint is counted in, by the semantic class of its pixel (dataset/naming.h).
enum FeatureClass : uint32_t {
    kFcGround,
    kFcTurf,
    kFcTrack,
    kFcVegetation,
    kFcObject,
    kFcSky,
    kFcOther,
    kFeatureClasses
};
inline constexpr std::array<const char*, kFeatureClasses> kFeatureClassNames = {"ground", "turf", "track", "vegetation",
                                                                                "object", "sky",  "other"};
using ClassCounts = std::array<uint64_t, kFeatureClasses>;

// ground (1), turf (11), track (12), vegetation (categories 2..5, felled 9, cut 10), object (8), sky (0), other.
FeatureClass featureClassOf(uint32_t semanticId);
// The class at a sub-pixel position: the semantic pixel that holds it (pixel centres at whole coordinates).
FeatureClass featureClassAt(const cv::Mat& semantic, cv::Point2f point);

struct Features {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors; // one row per keypoint
};

// At most kMaxFeatures keypoints of an 8-bit grey image, strongest first (ties broken by position, so the order
// never depends on the detector's internal order), with their descriptors.
inline constexpr size_t kMaxFeatures = 2000;
Features detectFeatures(Detector detector, const cv::Mat& gray);

struct Match {
    int query = 0, train = 0; // keypoint indices in the two feature sets
};
// Lowe's ratio test (best distance < kRatio * second best), brute force (Hamming for ORB / AKAZE, L2 for SIFT),
// one-to-one: a train keypoint claimed by several queries keeps none of them.
inline constexpr double kRatio = 0.8;
std::vector<Match> matchFeatures(Detector detector, const Features& query, const Features& train);

// Left-right matches of a rectified pair: for each left keypoint, the ratio test among the right keypoints whose
// row differs by at most kRowTolerancePx and whose disparity xLeft - xRight lies in [1, maxDisparity] (a lone
// candidate passes), one-to-one.
inline constexpr double kRowTolerancePx = 1.5;
std::vector<Match> matchStereo(Detector detector, const Features& left, const Features& right, double maxDisparity);

} // namespace sward
