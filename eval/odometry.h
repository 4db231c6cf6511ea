// Stereo visual odometry of a sward dataset against its ground-truth poses (docs/evaluation.md, "Odometry"):
// features (ORB / AKAZE / SIFT) detected in every left and right preview and counted per semantic class, stereo
// matches triangulated with calib.txt, the next frame's left features matched to them and its pose found by
// cv::solvePnPRansac, relative poses chained from the first frame's true pose; or a trajectory file evaluated
// instead. The trajectory metrics are eval/trajectory_metrics; the report files eval/odometry_report.
//
// Results are reproducible: frames are processed in parallel, but OpenCV runs single-threaded inside each, RANSAC
// starts from a fixed seed and results are merged in frame order, so every output file is bitwise identical
// whatever the thread count.
#pragma once

#include "eval/features.h"
#include "eval/trajectory_metrics.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sward {

// A named range of frames [first, end) (frame numbers) reported on its own: "bare", "grass", "tracks".
struct OdometrySegment {
    std::string name;
    uint32_t first = 0, end = 0;
};

struct OdometryOptions {
    std::string datasetDir;
    std::string outDir;    // report folder; empty: <datasetDir>/eval-odometry
    std::string posesFile; // a KITTI pose file to evaluate instead of running the VO; empty: run it
    Detector detector = Detector::Orb;
    bool truthMatcher = false; // correspondences from the ground-truth depth and poses instead of descriptors
    std::optional<std::pair<uint32_t, uint32_t>> frames; // [first, last) frame numbers; default: all
    std::vector<double> lengthsMetres = {1, 2, 5, 10};   // relative-error sub-sequence lengths
    std::vector<OdometrySegment> segments;
    double maxStepMetres = 2.0; // a motion moving the camera farther than this between two frames fails
    // A motion turning the camera more than this between two frames fails; default: the horizontal field of view
    // (2 atan(width / 2f) of calib.txt), beyond which the two views share nothing to match.
    std::optional<double> maxTurnDegrees;
    unsigned threads = 0;                        // frames processed at once; 0: hardware concurrency
    bool pictures = true;                        // the PNG plots
    std::function<void(const std::string&)> log; // progress lines; may be empty
};

// Fixed VO settings (docs/evaluation.md).
inline constexpr int kPnpIterations = 1000;
inline constexpr double kPnpReprojectionPx = 2.0;
inline constexpr double kPnpConfidence = 0.999;
inline constexpr uint32_t kMinInliers = 12; // fewer: the frame failed and keeps the previous motion
inline constexpr uint64_t kRansacSeed = 0x5eed;
inline constexpr int kTruthGridPx = 8; // --matcher truth samples every 8th pixel of every 8th row

// One frame's counts, per feature class (eval/features.h). Matches and inliers of frame i are those of the motion
// from frame i - 1 to i, counted by the class of the frame i - 1 keypoint (the triangulated one).
struct FrameOdometry {
    uint32_t frame = 0;
    ClassCounts keypoints{};       // left keypoints (truth matcher: grid samples with depth)
    ClassCounts rightKeypoints{};  // right keypoints (truth matcher: none)
    ClassCounts stereoMatches{};   // left keypoints with a left-right match, triangulated
    ClassCounts temporalMatches{}; // previous frame's triangulated keypoints matched into this frame: PnP input
    ClassCounts inliers{};         // those RANSAC kept
    bool failed = false;           // fewer than kMinInliers inliers, no solution or implausible: not measured
    bool implausible = false;      // solved, but beyond --max-step or --max-turn (a wrong PnP solution)
};

struct OdometryResult {
    std::string datasetDir;
    std::string method; // one line: detector settings, "ground-truth correspondences" or the pose file
    uint32_t width = 0, height = 0;
    std::vector<uint32_t> frameNumbers;
    std::vector<Pose> truth, estimate;
    std::vector<FrameOdometry> frames; // empty when the trajectory came from a pose file
    uint32_t failures = 0;
    uint32_t implausible = 0; // of the failures, those rejected by the plausibility gate
    TrajectoryMetrics metrics;
    std::vector<OdometrySegment> segments;
    double seconds = 0; // wall-clock time of the VO (log only)
};

// The plausibility gate: a frame-to-frame motion (x_b = R x_a + t) whose translation exceeds maxStepMetres or whose
// rotation angle exceeds maxTurnDegrees cannot be the camera's; the VO counts it as a failed frame.
bool plausibleMotion(const Pose& bFromA, double maxStepMetres, double maxTurnDegrees);

// Runs (or reads) the trajectory and evaluates it; writes nothing.
OdometryResult evaluateOdometry(const OdometryOptions& options);

// The whole tool: evaluates and writes the report folder atomically (it appears whole or not at all).
OdometryResult runOdometry(const OdometryOptions& options);

} // namespace sward
