#include "eval/odometry.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "common/staged_folder.h"
#include "common/stopwatch.h"
#include "dataset/naming.h"
#include "eval/dataset_reader.h"
#include "eval/number_format.h"
#include "eval/odometry_report.h"
#include "eval/opencv_threads.h"

#include <opencv2/calib3d.hpp>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace sward {

namespace {

// The rectified rig of calib.txt: the left camera's intrinsics and the baseline.
struct Rig {
    double f = 0, cx = 0, cy = 0, doffs = 0, baselineMetres = 0;
    uint32_t width = 0, height = 0;
    cv::Matx33d K() const { return {f, 0, cx, 0, f, cy, 0, 0, 1}; }
    double horizontalFovDegrees() const { return 2 * std::atan(width / (2 * f)) * 180 / CV_PI; }
};

struct Setup {
    const OdometryOptions* options = nullptr;
    std::string dir;
    Rig rig;
    std::vector<uint32_t> frames;
    std::vector<Pose> truth; // per entry of `frames`
};

// What the motion to the next frame needs of one frame: points in its camera, their class and, for the
// descriptor matcher, their features (point i belongs to keypoint i; NaN z: no stereo match).
struct FrameFeatures {
    Features left;
    std::vector<cv::Point3d> points;
    std::vector<uint8_t> classes;
};

struct Motion {
    Pose bFromA = Pose::eye(); // x_b = R x_a + t
    bool solved = false;
    ClassCounts matches{}, inliers{};
};

bool hasPoint(const cv::Point3d& p) {
    return !std::isnan(p.z);
}

void requireStereoDataset(const std::string& dir) {
    std::error_code ec;
    require(fs::is_directory(dir, ec), "dataset folder '" + dir + "' does not exist");
    require(fs::is_directory(dir + "/" + kPreviewRightFolder, ec),
            dir + " is a mono dataset (no '" + kPreviewRightFolder + "/'): stereo odometry needs a stereo rig");
}

Rig readRig(const std::string& dir) {
    const StereoCalib calib = readMiddleburyCalib(dir + "/" + kCalibFile);
    return {calib.cam0[0],           calib.cam0[2], calib.cam0[5], calib.doffs,
            calib.baselineMm * 1e-3, calib.width,   calib.height};
}

// The frames to evaluate (those with a left preview, restricted to options.frames) and their true poses.
void chooseFrames(Setup& setup) {
    const OdometryOptions& options = *setup.options;
    setup.frames = listDatasetFrames(setup.dir, kPreviewFolder);
    if (options.frames)
        std::erase_if(setup.frames,
                      [&](uint32_t f) { return f < options.frames->first || f >= options.frames->second; });
    require(setup.frames.size() >= 2, setup.dir + ": odometry needs at least 2 frames in '" + setup.dir + "/" +
                                          kPreviewFolder + "', found " + std::to_string(setup.frames.size()));
    const std::map<uint32_t, Pose> poses = readLeftPoses(setup.dir);
    for (uint32_t f : setup.frames) {
        auto it = poses.find(f);
        require(it != poses.end(), setup.dir + "/" + kFrameLogFile + " has no record of frame " + frameName(f));
        setup.truth.push_back(it->second);
    }
}

cv::Point3d triangulate(const Rig& rig, cv::Point2f left, double disparity) {
    const double z = rig.f * rig.baselineMetres / (disparity + rig.doffs);
    return {(left.x - rig.cx) * z / rig.f, (left.y - rig.cy) * z / rig.f, z};
}

// Descriptor matcher: features of both previews, counted per class, and the left ones triangulated.
FrameFeatures detectFrame(const Setup& setup, uint32_t frame, FrameOdometry& counts) {
    const Detector detector = setup.options->detector;
    const cv::Mat semantic = readSemantic(setup.dir, frame, setup.rig.width, setup.rig.height);
    FrameFeatures result;
    result.left = detectFeatures(detector, readPreview(setup.dir, kPreviewFolder, frame, true));
    const Features right = detectFeatures(detector, readPreview(setup.dir, kPreviewRightFolder, frame, true));
    result.points.assign(result.left.keypoints.size(), cv::Point3d(0, 0, NAN));
    for (const cv::KeyPoint& k : result.left.keypoints) {
        result.classes.push_back(uint8_t(featureClassAt(semantic, k.pt)));
        ++counts.keypoints[result.classes.back()];
    }
    for (const cv::KeyPoint& k : right.keypoints) ++counts.rightKeypoints[featureClassAt(semantic, k.pt)];
    const double maxDisparity = setup.rig.f * setup.rig.baselineMetres / 0.1; // anything beyond 10 cm
    for (const Match& m : matchStereo(detector, result.left, right, maxDisparity)) {
        const cv::Point2f l = result.left.keypoints[size_t(m.query)].pt;
        result.points[size_t(m.query)] =
            triangulate(setup.rig, l, double(l.x) - double(right.keypoints[size_t(m.train)].pt.x));
        ++counts.stereoMatches[result.classes[size_t(m.query)]];
    }
    return result;
}

// Truth matcher: every kTruthGridPx-th pixel with finite depth, back-projected exactly.
FrameFeatures sampleFrame(const Setup& setup, uint32_t frame, FrameOdometry& counts) {
    const Rig& rig = setup.rig;
    const cv::Mat semantic = readSemantic(setup.dir, frame, rig.width, rig.height);
    const std::vector<float> depth = readDepth(setup.dir, frame, rig.width, rig.height);
    FrameFeatures result;
    for (uint32_t v = kTruthGridPx / 2; v < rig.height; v += kTruthGridPx)
        for (uint32_t u = kTruthGridPx / 2; u < rig.width; u += kTruthGridPx) {
            const double z = depth[size_t(v) * rig.width + u];
            if (!std::isfinite(z) || z <= 0) continue;
            result.points.push_back({(u - rig.cx) * z / rig.f, (v - rig.cy) * z / rig.f, z});
            result.classes.push_back(uint8_t(featureClassOf(semantic.at<uint8_t>(int(v), int(u)))));
            ++counts.keypoints[result.classes.back()];
            ++counts.stereoMatches[result.classes.back()];
        }
    return result;
}

// cv::solvePnPRansac on the correspondences; RANSAC's random samples come from OpenCV's generator, seeded here.
Motion solveMotion(const Rig& rig, const std::vector<cv::Point3d>& object, const std::vector<cv::Point2d>& image,
                   const std::vector<uint8_t>& classes) {
    Motion motion;
    for (uint8_t c : classes) ++motion.matches[c];
    if (object.size() < 4) return motion;
    cv::setRNGSeed(int(kRansacSeed));
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    const bool ok = cv::solvePnPRansac(object, image, rig.K(), cv::noArray(), rvec, tvec, false, kPnpIterations,
                                       float(kPnpReprojectionPx), kPnpConfidence, inliers, cv::SOLVEPNP_ITERATIVE);
    for (int i : inliers) ++motion.inliers[classes[size_t(i)]];
    if (!ok || inliers.size() < kMinInliers) return motion;
    cv::Matx33d r;
    cv::Rodrigues(rvec, r);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) motion.bFromA(i, j) = r(i, j);
        motion.bFromA(i, 3) = tvec.at<double>(i);
    }
    motion.solved = true;
    return motion;
}

// Descriptor matcher: frame a's triangulated keypoints matched into frame b's left view.
Motion descriptorMotion(const Setup& setup, const FrameFeatures& a, const FrameFeatures& b) {
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    std::vector<uint8_t> classes;
    for (const Match& m : matchFeatures(setup.options->detector, a.left, b.left)) {
        if (!hasPoint(a.points[size_t(m.query)])) continue;
        object.push_back(a.points[size_t(m.query)]);
        const cv::Point2f p = b.left.keypoints[size_t(m.train)].pt;
        image.push_back({p.x, p.y});
        classes.push_back(a.classes[size_t(m.query)]);
    }
    return solveMotion(setup.rig, object, image, classes);
}

// Truth matcher: frame a's points projected into frame b with the true poses (those in front and inside).
Motion truthMotion(const Setup& setup, const FrameFeatures& a, const Pose& poseA, const Pose& poseB) {
    const Pose bFromA = relativePose(poseB, poseA);
    const Rig& rig = setup.rig;
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    std::vector<uint8_t> classes;
    for (size_t i = 0; i < a.points.size(); ++i) {
        const cv::Vec4d q = bFromA * cv::Vec4d(a.points[i].x, a.points[i].y, a.points[i].z, 1);
        if (q[2] <= 1e-3) continue;
        const double u = rig.f * q[0] / q[2] + rig.cx, v = rig.f * q[1] / q[2] + rig.cy;
        if (u < -0.5 || v < -0.5 || u > rig.width - 0.5 || v > rig.height - 0.5) continue;
        object.push_back(a.points[i]);
        image.push_back({u, v});
        classes.push_back(a.classes[i]);
    }
    return solveMotion(rig, object, image, classes);
}

double maxTurnDegrees(const Setup& setup) {
    return setup.options->maxTurnDegrees.value_or(setup.rig.horizontalFovDegrees());
}

// The VO over the chosen frames: features per frame, then motions per consecutive pair, both in parallel with
// one output slot per index; the chain is built in frame order.
void runVisualOdometry(const Setup& setup, OdometryResult& result) {
    SingleThreadedOpenCV singleThreaded;
    const OdometryOptions& options = *setup.options;
    const uint32_t n = uint32_t(setup.frames.size());
    std::vector<FrameFeatures> features(n);
    result.frames.assign(n, {});
    parallelFor(n, options.threads, [&](uint32_t i, uint32_t) {
        result.frames[i].frame = setup.frames[i];
        features[i] = options.truthMatcher ? sampleFrame(setup, setup.frames[i], result.frames[i])
                                           : detectFrame(setup, setup.frames[i], result.frames[i]);
    });
    std::vector<Motion> motions(n);
    parallelFor(n - 1, options.threads, [&](uint32_t i, uint32_t) {
        motions[i + 1] = options.truthMatcher ? truthMotion(setup, features[i], setup.truth[i], setup.truth[i + 1])
                                              : descriptorMotion(setup, features[i], features[i + 1]);
    });
    const double maxTurn = maxTurnDegrees(setup);
    result.estimate = {setup.truth[0]};
    Pose last = Pose::eye(); // a failed frame repeats the last measured motion (constant velocity)
    for (uint32_t i = 1; i < n; ++i) {
        FrameOdometry& f = result.frames[i];
        f.temporalMatches = motions[i].matches;
        f.inliers = motions[i].inliers;
        f.implausible = motions[i].solved && !plausibleMotion(motions[i].bFromA, options.maxStepMetres, maxTurn);
        f.failed = !motions[i].solved || f.implausible;
        if (!f.failed) last = motions[i].bFromA;
        result.failures += f.failed;
        result.implausible += f.implausible;
        result.estimate.push_back(result.estimate.back() * inverseRigid(last));
    }
}

std::string gateDescription(const Setup& setup) {
    return "; a motion over " + metres(setup.options->maxStepMetres) + " m or " + fixed(maxTurnDegrees(setup), 1) +
           " deg" + (setup.options->maxTurnDegrees ? "" : " (the field of view)") + " per frame fails";
}

void requireSegments(const Setup& setup) {
    for (const OdometrySegment& s : setup.options->segments)
        require(s.first < s.end,
                "segment '" + s.name + "': empty frame range " + std::to_string(s.first) + ":" + std::to_string(s.end));
}

} // namespace

bool plausibleMotion(const Pose& bFromA, double maxStepMetres, double maxTurnDegrees) {
    const double step = std::hypot(bFromA(0, 3), bFromA(1, 3), bFromA(2, 3));
    return step <= maxStepMetres && rotationAngleDegrees(bFromA) <= maxTurnDegrees;
}

OdometryResult evaluateOdometry(const OdometryOptions& options) {
    Setup setup;
    setup.options = &options;
    setup.dir = options.datasetDir;
    require(!setup.dir.empty(), "no dataset folder given");
    OdometryResult result;
    result.datasetDir = setup.dir;
    if (options.posesFile.empty()) {
        requireStereoDataset(setup.dir);
        setup.rig = readRig(setup.dir);
    }
    requireSegments(setup);
    chooseFrames(setup);
    result.frameNumbers = setup.frames;
    result.truth = setup.truth;
    result.width = setup.rig.width;
    result.height = setup.rig.height;
    const Stopwatch estimation;
    if (!options.posesFile.empty()) {
        result.method = "poses read from " + options.posesFile;
        result.estimate = readKittiPoses(options.posesFile);
        require(result.estimate.size() == setup.frames.size(),
                options.posesFile + ": " + std::to_string(result.estimate.size()) + " poses for " +
                    std::to_string(setup.frames.size()) + " frames (one line per frame of the dataset's preview/)");
    } else {
        result.method = options.truthMatcher ? "ground-truth correspondences (depth + poses), every " +
                                                   std::to_string(kTruthGridPx) + "th pixel"
                                             : detectorDescription(options.detector);
        result.method += gateDescription(setup);
        runVisualOdometry(setup, result);
    }
    result.seconds = estimation.seconds();
    result.metrics = evaluateTrajectory(result.truth, result.estimate, options.lengthsMetres);
    result.segments = options.segments;
    return result;
}

OdometryResult runOdometry(const OdometryOptions& options) {
    const std::string outDir = options.outDir.empty() ? options.datasetDir + "/eval-odometry" : options.outDir;
    OdometryResult result = evaluateOdometry(options);
    // The report appears whole or not at all, in a folder locked for one writer; DATASET/eval-odometry as a link
    // is refused.
    StagedFolder staged(outDir, "report folder", !options.outDir.empty());
    writeOdometryReport(result, staged.path(), options.pictures);
    staged.commit();
    if (options.log) {
        const TrajectoryMetrics& m = result.metrics;
        options.log(result.datasetDir + ": " + std::to_string(m.frames) + " frames, " + fixed(m.pathMetres, 2) +
                    " m, ATE " + fixed(m.ateFirstFrameRmse, 4) + " m (first-frame aligned), " +
                    fixed(m.ateUmeyamaRmse, 4) + " m (rigid), drift " + fixed(m.driftPercent, 2) + " %, " +
                    std::to_string(result.failures) + " failed frames (" + std::to_string(result.implausible) +
                    " implausible); " + fixed(result.seconds, 2) + " s");
        options.log("report written to " + outDir + "/report.md");
    }
    return result;
}

} // namespace sward
