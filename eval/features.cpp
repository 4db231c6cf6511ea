#include "eval/features.h"

#include "common/error.h"
#include "dataset/naming.h"

#include <opencv2/features2d.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string_view>

namespace sward {

namespace {

// Fixed detector parameters (docs/evaluation.md): OpenCV's defaults except ORB's and SIFT's feature budget, which
// is set to kMaxFeatures so the three detectors are compared at the same cap.
cv::Ptr<cv::Feature2D> makeDetector(Detector detector) {
    switch (detector) {
    case Detector::Orb:
        return cv::ORB::create(int(kMaxFeatures), 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20);
    case Detector::Akaze:
        return cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_MLDB, 0, 3, 0.001f, 4, 4, cv::KAZE::DIFF_PM_G2);
    case Detector::Sift:
        return cv::SIFT::create(int(kMaxFeatures), 3, 0.04, 10, 1.6);
    }
    throw Error("unknown detector");
}

// The strongest keypoints first; equal responses by position, size and angle, so the order (and which keypoints
// survive the cap) is a function of the keypoints alone.
void keepStrongest(std::vector<cv::KeyPoint>& keypoints) {
    auto key = [](const cv::KeyPoint& k) {
        return std::make_tuple(-k.response, k.pt.y, k.pt.x, k.size, k.angle, k.octave);
    };
    std::sort(keypoints.begin(), keypoints.end(),
              [&](const cv::KeyPoint& a, const cv::KeyPoint& b) { return key(a) < key(b); });
    if (keypoints.size() > kMaxFeatures) keypoints.resize(kMaxFeatures);
}

int normOf(Detector detector) {
    return detector == Detector::Sift ? cv::NORM_L2 : cv::NORM_HAMMING;
}

} // namespace

Detector parseDetector(const std::string& name) {
    if (name == "orb") return Detector::Orb;
    if (name == "akaze") return Detector::Akaze;
    if (name == "sift") return Detector::Sift;
    throw Error("unknown detector '" + name + "' (expected orb, akaze or sift)");
}

const char* detectorName(Detector detector) {
    static const char* names[] = {"orb", "akaze", "sift"};
    return names[int(detector)];
}

std::string detectorDescription(Detector detector) {
    const std::string cap = std::to_string(kMaxFeatures);
    switch (detector) {
    case Detector::Orb:
        return "ORB: nfeatures " + cap +
               ", scaleFactor 1.2, nlevels 8, edgeThreshold 31, HARRIS_SCORE, patchSize 31, "
               "fastThreshold 20; Hamming distance";
    case Detector::Akaze:
        return "AKAZE: MLDB descriptor (full size, 3 channels), threshold 0.001, 4 octaves x 4 layers, DIFF_PM_G2; "
               "strongest " +
               cap + " kept; Hamming distance";
    case Detector::Sift:
        return "SIFT: nfeatures " + cap +
               ", 3 octave layers, contrastThreshold 0.04, edgeThreshold 10, sigma 1.6; "
               "L2 distance";
    }
    return "";
}

FeatureClass featureClassOf(uint32_t semanticId) {
    const SemanticClass* c = findSemanticClass(semanticId);
    if (!c) return kFcOther;
    const std::string_view name = c->name, group = c->group;
    if (name == "ground") return kFcGround;
    if (name == "turf") return kFcTurf;
    if (name == "track") return kFcTrack;
    if (group == "vegetation") return kFcVegetation;
    if (group == "object") return kFcObject;
    if (group == "sky") return kFcSky;
    return kFcOther;
}

FeatureClass featureClassAt(const cv::Mat& semantic, cv::Point2f point) {
    const int x = std::clamp(int(std::lround(point.x)), 0, semantic.cols - 1);
    const int y = std::clamp(int(std::lround(point.y)), 0, semantic.rows - 1);
    return featureClassOf(semantic.at<uint8_t>(y, x));
}

Features detectFeatures(Detector detector, const cv::Mat& gray) {
    cv::Ptr<cv::Feature2D> algorithm = makeDetector(detector);
    Features f;
    algorithm->detect(gray, f.keypoints);
    keepStrongest(f.keypoints);
    // compute() may drop keypoints (too near the border for the descriptor) but keeps the order of the rest.
    algorithm->compute(gray, f.keypoints, f.descriptors);
    return f;
}

std::vector<Match> matchFeatures(Detector detector, const Features& query, const Features& train) {
    std::vector<Match> matches;
    if (query.keypoints.empty() || train.keypoints.size() < 2) return matches;
    cv::BFMatcher matcher(normOf(detector));
    std::vector<std::vector<cv::DMatch>> knn;
    matcher.knnMatch(query.descriptors, train.descriptors, knn, 2);
    std::vector<int> claims(train.keypoints.size(), 0);
    for (const auto& m : knn)
        if (m.size() == 2 && m[0].distance < kRatio * m[1].distance) {
            matches.push_back({m[0].queryIdx, m[0].trainIdx});
            ++claims[size_t(m[0].trainIdx)];
        }
    std::erase_if(matches, [&](const Match& m) { return claims[size_t(m.train)] > 1; });
    return matches;
}

std::vector<Match> matchStereo(Detector detector, const Features& left, const Features& right, double maxDisparity) {
    // The ratio test runs among the candidates the epipolar constraint allows (same row, disparity in range), not
    // among all right keypoints: grass repeats itself across the image, and a look-alike on another row must not
    // make a correct match ambiguous.
    std::vector<int> byRow(right.keypoints.size());
    std::iota(byRow.begin(), byRow.end(), 0);
    auto rowOf = [&](int i) { return right.keypoints[size_t(i)].pt.y; };
    std::stable_sort(byRow.begin(), byRow.end(), [&](int a, int b) { return rowOf(a) < rowOf(b); });
    const int norm = normOf(detector);
    std::vector<Match> matches;
    std::vector<int> claims(right.keypoints.size(), 0);
    for (int q = 0; q < int(left.keypoints.size()); ++q) {
        const cv::Point2f l = left.keypoints[size_t(q)].pt;
        auto first = std::lower_bound(byRow.begin(), byRow.end(), l.y - kRowTolerancePx,
                                      [&](int i, double y) { return rowOf(i) < y; });
        double best = INFINITY, second = INFINITY;
        int bestIndex = -1;
        for (auto it = first; it != byRow.end() && rowOf(*it) <= l.y + kRowTolerancePx; ++it) {
            const double d = double(l.x) - double(right.keypoints[size_t(*it)].pt.x);
            if (d < 1 || d > maxDisparity) continue; // d >= 1 px: at most f * B metres away
            const double distance = cv::norm(left.descriptors.row(q), right.descriptors.row(*it), norm);
            if (distance < best) {
                second = best;
                best = distance;
                bestIndex = *it;
            } else if (distance < second) {
                second = distance;
            }
        }
        // A lone candidate has no rival: accept it (second = infinity).
        if (bestIndex >= 0 && best < kRatio * second) {
            matches.push_back({q, bestIndex});
            ++claims[size_t(bestIndex)];
        }
    }
    std::erase_if(matches, [&](const Match& m) { return claims[size_t(m.train)] > 1; });
    return matches;
}

} // namespace sward
