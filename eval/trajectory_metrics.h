// Trajectory error metrics of a camera path against ground truth (docs/evaluation.md, "Odometry"): absolute
// trajectory error (ATE) after two alignments, KITTI odometry relative errors over sub-sequences of given lengths,
// and per-frame relative pose errors; plus KITTI's pose file format. Poses are 4x4 camera-to-world matrices of
// the left camera (OpenCV axes), one per frame; the two trajectories have the same frames in the same order.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

using Pose = cv::Matx44d; // camera-to-world, row-major, last row 0 0 0 1

// Rotation angle of a pose's 3x3 part in degrees (0 .. 180).
double rotationAngleDegrees(const Pose& pose);
// inv(a) * b for rigid poses (the motion from a to b in a's frame).
Pose relativePose(const Pose& a, const Pose& b);
Pose inverseRigid(const Pose& pose);

// What readKittiPoses takes as a camera pose: max |R^T R - I| and |det R - 1| at most kPoseRotationTolerance
// (files written with 6 significant digits are off by about 1e-6), each coordinate of the position within
// kMaxPoseTranslationMetres (a thousand kilometres: far beyond any scene, far short of overflowing the metrics'
// squares, as 1e308 does).
inline constexpr double kPoseRotationTolerance = 1e-3;
inline constexpr double kMaxPoseTranslationMetres = 1e6;

// KITTI odometry pose file: one line per frame, the first 3 rows of the 4x4 pose row-major (12 numbers).
// Throws sward::Error naming the file and line on anything else (a line of the wrong count, a non-finite number,
// a 3x3 part that is not a rotation, a position beyond kMaxPoseTranslationMetres).
std::vector<Pose> readKittiPoses(const std::string& path);
std::string kittiPosesText(const std::vector<Pose>& poses); // "%.17g": read back bitwise

// The rigid transform (rotation + translation, no scale) that maps `from` onto `to` in the least-squares sense
// (Umeyama 1991 with the scale fixed at 1); both the same size, at least one point.
Pose umeyamaRigid(const std::vector<cv::Vec3d>& from, const std::vector<cv::Vec3d>& to);

// KITTI's relative error for one sub-sequence length.
struct RelativeError {
    double lengthMetres = 0;
    uint32_t pairs = 0;               // sub-sequences of this length in the path; 0: the path is shorter
    double translationPercent = NAN;  // mean over pairs of |translation error| / length * 100
    double rotationDegPerMetre = NAN; // mean over pairs of rotation error angle / length
};

// The error of one frame's motion from the previous frame (frame 0: zeros).
struct FramePoseError {
    double translationMetres = 0; // |t| of inv(gt motion) * estimated motion
    double rotationDegrees = 0;   // its rotation angle
    double stepMetres = 0;        // ground-truth distance travelled from the previous frame
    double positionError = 0;     // |estimate - truth| position after the first-frame alignment
};

struct TrajectoryMetrics {
    uint32_t frames = 0;
    double pathMetres = 0;            // ground-truth distance travelled
    double ateFirstFrameRmse = 0;     // after aligning the estimate's first pose onto the truth's
    double ateUmeyamaRmse = 0;        // after the best rigid alignment of all positions (no scale)
    double endErrorMetres = 0;        // last frame's position error after the first-frame alignment
    double driftPercent = NAN;        // mean translational relative error over every length and pair: metres per 100 m
    double rotationDegPerMetre = NAN; // the same mean for the rotational error
    std::vector<RelativeError> relative; // per length
    std::vector<FramePoseError> perFrame;
};

// Metrics of `estimate` against `truth` (same size, at least one pose). `lengthsMetres`: sub-sequence lengths,
// positive. A sub-sequence from frame i ends at the first frame j whose ground-truth distance from i is >= the
// length (KITTI takes every 10th start frame and ">"; we take every frame and ">=").
TrajectoryMetrics evaluateTrajectory(const std::vector<Pose>& truth, const std::vector<Pose>& estimate,
                                     const std::vector<double>& lengthsMetres);

// Mean translational error in % and rotational error in deg/m of the frame motions in [first, end): the sum of
// per-frame errors divided by the distance travelled (for per-segment drift); NaN when it travelled nothing.
struct SegmentDrift {
    double distanceMetres = 0;
    double translationPercent = NAN;
    double rotationDegPerMetre = NAN;
};
SegmentDrift segmentDrift(const TrajectoryMetrics& metrics, uint32_t first, uint32_t end);

} // namespace sward
