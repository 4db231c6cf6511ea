#include "eval/odometry_report.h"

#include "common/atomic_file.h"
#include "eval/number_format.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

// The counts of one kind over some frames, summed per class.
using CountOf = ClassCounts FrameOdometry::*;
constexpr std::pair<const char*, CountOf> kCounts[] = {{"keypoints", &FrameOdometry::keypoints},
                                                       {"right_keypoints", &FrameOdometry::rightKeypoints},
                                                       {"stereo_matches", &FrameOdometry::stereoMatches},
                                                       {"temporal_matches", &FrameOdometry::temporalMatches},
                                                       {"inliers", &FrameOdometry::inliers}};

// Frame motions in the frames [first, end): each frame but frame 0 ends one.
double motionsIn(size_t first, size_t end) {
    const size_t from = std::max<size_t>(first, 1);
    return end > from ? double(end - from) : 0.0;
}

uint64_t total(const ClassCounts& c) {
    uint64_t n = 0;
    for (uint64_t v : c) n += v;
    return n;
}

// Indices into result.frames of the frames numbered [first, end).
std::pair<size_t, size_t> indexRange(const OdometryResult& r, uint32_t first, uint32_t end) {
    const auto b = std::lower_bound(r.frameNumbers.begin(), r.frameNumbers.end(), first);
    const auto e = std::lower_bound(r.frameNumbers.begin(), r.frameNumbers.end(), end);
    return {size_t(b - r.frameNumbers.begin()), size_t(e - r.frameNumbers.begin())};
}

ClassCounts sum(const OdometryResult& r, CountOf count, size_t first, size_t end) {
    ClassCounts s{};
    for (size_t i = first; i < std::min(end, r.frames.size()); ++i)
        for (size_t c = 0; c < kFeatureClasses; ++c) s[c] += (r.frames[i].*count)[c];
    return s;
}

nlohmann::json countsJson(const ClassCounts& c, double divisor = 1) {
    nlohmann::json j = nlohmann::json::object();
    for (size_t k = 0; k < kFeatureClasses; ++k)
        j[kFeatureClassNames[k]] = divisor == 1 ? nlohmann::json(c[k]) : nlohmann::json(double(c[k]) / divisor);
    j["all"] = divisor == 1 ? nlohmann::json(total(c)) : nlohmann::json(double(total(c)) / divisor);
    return j;
}

// Counts summed over [first, end), and their means per frame; motions (temporal matches, inliers) per motion.
nlohmann::json featuresJson(const OdometryResult& r, size_t first, size_t end) {
    nlohmann::json j;
    const double frames = double(end - first), motions = motionsIn(first, end);
    for (const auto& [name, count] : kCounts) {
        const bool perMotion = count == &FrameOdometry::temporalMatches || count == &FrameOdometry::inliers;
        const ClassCounts s = sum(r, count, first, end);
        j[name] = countsJson(s);
        j[std::string(name) + "_per_frame"] = countsJson(s, std::max(1.0, perMotion ? motions : frames));
    }
    return j;
}

uint32_t failuresIn(const OdometryResult& r, size_t first, size_t end) {
    uint32_t n = 0;
    for (size_t i = first; i < std::min(end, r.frames.size()); ++i) n += r.frames[i].failed;
    return n;
}

nlohmann::json segmentJson(const OdometryResult& r, const OdometrySegment& s) {
    const auto [first, end] = indexRange(r, s.first, s.end);
    const SegmentDrift d = segmentDrift(r.metrics, uint32_t(first), uint32_t(end));
    nlohmann::json j = {{"name", s.name},
                        {"first_frame", s.first},
                        {"end_frame", s.end},
                        {"frames", end - first},
                        {"distance_m", d.distanceMetres},
                        {"drift_percent", d.translationPercent},
                        {"rotation_deg_per_m", d.rotationDegPerMetre}};
    if (!r.frames.empty()) {
        j["failed_frames"] = failuresIn(r, first, end);
        j["features"] = featuresJson(r, first, end);
    }
    return j;
}

nlohmann::json perFrameJson(const OdometryResult& r) {
    nlohmann::json frames = nlohmann::json::array();
    for (size_t i = 0; i < r.frameNumbers.size(); ++i) {
        const FramePoseError& e = r.metrics.perFrame[i];
        nlohmann::json j = {{"frame", r.frameNumbers[i]},
                            {"step_m", e.stepMetres},
                            {"translation_error_m", e.translationMetres},
                            {"rotation_error_deg", e.rotationDegrees},
                            {"position_error_m", e.positionError}};
        if (!r.frames.empty()) {
            const FrameOdometry& f = r.frames[i];
            for (const auto& [name, count] : kCounts) j[name] = countsJson(f.*count);
            j["failed"] = f.failed;
            j["implausible"] = f.implausible;
        }
        frames.push_back(std::move(j));
    }
    return frames;
}

} // namespace

std::string odometryJson(const OdometryResult& r) {
    const TrajectoryMetrics& m = r.metrics;
    nlohmann::json j = {{"dataset", r.datasetDir},
                        {"method", r.method},
                        {"frames", m.frames},
                        {"path_m", m.pathMetres},
                        {"ate_first_frame_rmse_m", m.ateFirstFrameRmse},
                        {"ate_rigid_rmse_m", m.ateUmeyamaRmse},
                        {"end_error_m", m.endErrorMetres},
                        {"drift_percent", m.driftPercent},
                        {"rotation_deg_per_m", m.rotationDegPerMetre}};
    nlohmann::json relative = nlohmann::json::array();
    for (const RelativeError& e : m.relative)
        relative.push_back({{"length_m", e.lengthMetres},
                            {"pairs", e.pairs},
                            {"translation_percent", e.translationPercent},
                            {"rotation_deg_per_m", e.rotationDegPerMetre}});
    j["relative_errors"] = relative;
    if (!r.frames.empty()) {
        j["failed_frames"] = r.failures;
        j["implausible_frames"] = r.implausible;
        j["feature_classes"] = kFeatureClassNames;
        j["features"] = featuresJson(r, 0, r.frames.size());
    }
    nlohmann::json segments = nlohmann::json::array();
    for (const OdometrySegment& s : r.segments) segments.push_back(segmentJson(r, s));
    j["segments"] = segments;
    j["per_frame"] = perFrameJson(r);
    return j.dump(2) + "\n";
}

namespace {

std::string classHeader(const std::string& first) {
    std::string h = "| " + first + " |", rule = "|---|";
    for (const char* name : kFeatureClassNames) {
        h += std::string(" ") + name + " |";
        rule += "---:|";
    }
    return h + " all |\n" + rule + "---:|\n";
}

std::string classRow(const std::string& label, const ClassCounts& c, double divisor) {
    std::string row = "| " + label + " |";
    for (uint64_t v : c) row += " " + fixed(double(v) / divisor, divisor == 1 ? 0 : 1) + " |";
    return row + " " + fixed(double(total(c)) / divisor, divisor == 1 ? 0 : 1) + " |\n";
}

std::string featuresTable(const OdometryResult& r, size_t first, size_t end) {
    const double frames = std::max(1.0, double(end - first));
    const double motions = std::max(1.0, motionsIn(first, end));
    std::string t = classHeader("per frame (mean)");
    t += classRow("left keypoints", sum(r, &FrameOdometry::keypoints, first, end), frames);
    t += classRow("right keypoints", sum(r, &FrameOdometry::rightKeypoints, first, end), frames);
    t += classRow("stereo matches", sum(r, &FrameOdometry::stereoMatches, first, end), frames);
    t += classRow("frame-to-frame matches", sum(r, &FrameOdometry::temporalMatches, first, end), motions);
    t += classRow("RANSAC inliers", sum(r, &FrameOdometry::inliers, first, end), motions);
    return t;
}

std::string segmentsTable(const OdometryResult& r) {
    std::string t = "| segment | frames | distance (m) | drift (%) | rotation (deg/m) | failed | keypoints | stereo "
                    "matches | inliers | inliers on ground / turf | inliers on vegetation | inliers on track |\n|---|"
                    "---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const OdometrySegment& s : r.segments) {
        const auto [first, end] = indexRange(r, s.first, s.end);
        const SegmentDrift d = segmentDrift(r.metrics, uint32_t(first), uint32_t(end));
        t += "| " + s.name + " (" + std::to_string(s.first) + ":" + std::to_string(s.end) + ") | " +
             std::to_string(end - first) + " | " + fixed(d.distanceMetres, 2) + " | " + fixed(d.translationPercent, 2) +
             " | " + fixed(d.rotationDegPerMetre, 3) + " |";
        if (r.frames.empty()) {
            t += " | | | | | | |\n";
            continue;
        }
        const double frames = std::max(1.0, double(end - first));
        const double motions = std::max(1.0, motionsIn(first, end));
        const ClassCounts inliers = sum(r, &FrameOdometry::inliers, first, end);
        t += " " + std::to_string(failuresIn(r, first, end)) + " | " +
             fixed(double(total(sum(r, &FrameOdometry::keypoints, first, end))) / frames, 1) + " | " +
             fixed(double(total(sum(r, &FrameOdometry::stereoMatches, first, end))) / frames, 1) + " | " +
             fixed(double(total(inliers)) / motions, 1) + " | " +
             fixed(double(inliers[kFcGround] + inliers[kFcTurf]) / motions, 1) + " | " +
             fixed(double(inliers[kFcVegetation]) / motions, 1) + " | " +
             fixed(double(inliers[kFcTrack]) / motions, 1) + " |\n";
    }
    return t;
}

} // namespace

std::string odometryMarkdown(const OdometryResult& r, bool pictures) {
    const TrajectoryMetrics& m = r.metrics;
    std::string md = "# Odometry: " + r.datasetDir + "\n\n" + r.method + "\n\n";
    md += "| metric | value |\n|---|---:|\n";
    md += "| frames | " + std::to_string(m.frames) + " |\n";
    md += "| path length (m) | " + fixed(m.pathMetres, 3) + " |\n";
    md += "| ATE RMSE, first frame aligned (m) | " + fixed(m.ateFirstFrameRmse, 4) + " |\n";
    md += "| ATE RMSE, rigid (Umeyama) alignment (m) | " + fixed(m.ateUmeyamaRmse, 4) + " |\n";
    md += "| end-point error (m) | " + fixed(m.endErrorMetres, 4) + " |\n";
    md += "| drift: translational relative error (%, m per 100 m) | " + fixed(m.driftPercent, 3) + " |\n";
    md += "| rotational relative error (deg/m) | " + fixed(m.rotationDegPerMetre, 4) + " |\n";
    if (!r.frames.empty())
        md += "| failed frames (< " + std::to_string(kMinInliers) + " inliers, or implausible) | " +
              std::to_string(r.failures) + " |\n| of them implausible (beyond the step or turn bound) | " +
              std::to_string(r.implausible) + " |\n";
    md += "\n## Relative errors (KITTI, lengths scaled to the path)\n\n| length (m) | pairs | translation (%) | "
          "rotation (deg/m) |\n|---:|---:|---:|---:|\n";
    for (const RelativeError& e : m.relative)
        md += "| " + metres(e.lengthMetres) + " | " + std::to_string(e.pairs) + " | " + fixed(e.translationPercent, 3) +
              " | " + fixed(e.rotationDegPerMetre, 4) + " |\n";
    if (!r.segments.empty()) md += "\n## Segments\n\n" + segmentsTable(r);
    if (!r.frames.empty()) {
        md += "\n## Features by class (whole sequence)\n\n" + featuresTable(r, 0, r.frames.size());
        for (const OdometrySegment& s : r.segments) {
            const auto [first, end] = indexRange(r, s.first, s.end);
            md += "\n### Segment " + s.name + "\n\n" + featuresTable(r, first, end);
        }
    }
    if (pictures) {
        md += "\n## Plots\n\n![trajectory](trajectory.png)\n";
        if (!r.frames.empty()) md += "\n![features](features.png)\n\n![inliers](inliers.png)\n";
    }
    return md;
}

void writeOdometryReport(const OdometryResult& result, const std::string& dir, bool pictures) {
    writeTextAtomically(dir + "/metrics.json", odometryJson(result));
    writeTextAtomically(dir + "/report.md", odometryMarkdown(result, pictures));
    writeTextAtomically(dir + "/poses_estimate.txt", kittiPosesText(result.estimate));
    writeTextAtomically(dir + "/poses_truth.txt", kittiPosesText(result.truth));
    if (pictures) writeOdometryPlots(result, dir);
}

} // namespace sward
