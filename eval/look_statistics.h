// The realism statistics of `sward-eval look` (docs/evaluation.md, "Realism statistics"): pure functions from one
// image and a region mask to numbers, the same for a sward preview and a real photograph. Every statistic is NaN
// ("null" in look.json) when the region holds nothing it can be measured on.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace sward {

// Fixed settings (docs/evaluation.md).
inline constexpr int kLookPyramidLevels = 5;         // Laplacian levels 0..4
inline constexpr int kLookKeypointErosionPx = 8;     // keypoints are counted in the region eroded by this much
inline constexpr int kLookOrbFeatures = 100000;      // ORB's budget: high enough never to bind at 640x480
inline constexpr int kLookFastThreshold = 20;        // FAST, with non-max suppression
inline constexpr double kLookSharpThreshold = 0.02;  // local RMS of the high-pass above this: sharp texture
inline constexpr int kLookNoiseBlockPx = 16;         // noise-floor blocks
inline constexpr double kLookNoisePercentile = 0.10; // the noise floor: this percentile of the block std
inline constexpr double kLookGreyConstantStd = 1e-6; // d/dx with a smaller std is constant: no kurtosis
inline constexpr int kLookHistogramBins = 64;

// One image prepared once for every region: grey (luma of the sRGB values, OpenCV's BGR2GRAY weights
// 0.299 R + 0.587 G + 0.114 B, on values in [0, 1]) and HSV in [0, 1] (hue in degrees), the frame's mean grey
// subtracted before any filter (so a flat image filters to exact zeros), its gradients and Laplacian pyramid, and
// the whole frame's keypoints.
struct LookImage {
    cv::Mat grey;                                      // CV_32F in [0, 1]
    cv::Mat centred;                                   // CV_32F: grey minus the frame's mean grey
    cv::Mat hue;                                       // CV_64F degrees [0, 360)
    cv::Mat saturation;                                // CV_64F [0, 1]: (max - min) / max, 0 where max = 0
    cv::Mat value;                                     // CV_64F [0, 1]: max of R, G, B
    cv::Mat clipped;                                   // CV_8U: 255 where a channel is 0 or 1 (0 or 255 in 8 bits)
    cv::Mat dx, dy;                                    // CV_64F: Sobel 3x3 / 8 of the grey
    std::vector<cv::Mat> laplacian;                    // CV_32F: Laplacian-pyramid levels 0 .. kLookPyramidLevels - 1
    std::array<std::vector<cv::Point2f>, 3> keypoints; // ORB, SIFT, FAST, on the whole frame's 8-bit grey
};

// `bgr`: CV_8UC3 (values / 255) or CV_32FC3 in [0, 1]. The detectors run on the grey rounded to 8 bits.
// `detectKeypoints` false leaves the keypoint lists empty (tests of the other statistics).
LookImage prepareLookImage(const cv::Mat& bgr, bool detectKeypoints = true);

// Every statistic of one region of one image.
struct LookStatistics {
    uint64_t pixels = 0;         // region pixels
    double greyMean = NAN;       // mean grey (reported: the Laplacian's divisor)
    double greyStd = NAN;        // std of grey
    double saturationMean = NAN; // HSV saturation mean
    double valueStd = NAN;       // HSV value std
    double hueStdDegrees = NAN;  // saturation-weighted circular std of hue: sqrt(-2 ln R), R the mean resultant
    double gradientMean = NAN;   // |Sobel| / 8 on grey: mean
    double gradientP99 = NAN;    // ... its 99th percentile
    double dxKurtosis = NAN;     // excess kurtosis of Sobel d/dx / 8 (NaN when d/dx is constant)
    std::array<double, kLookPyramidLevels> laplacianRms{NAN, NAN, NAN, NAN, NAN}; // / greyMean
    double spectrumSlope = NAN;                                 // log-log power slope over [2/64, 0.4] cycles / px
    double spectrumSlopeHigh = NAN;                             // ... over [0.1, 0.4]
    uint64_t spectrumWindows = 0;                               // 64x64 windows inside the region
    std::array<double, 3> keypointsPerMegapixel{NAN, NAN, NAN}; // ORB, SIFT, FAST
    uint64_t erodedPixels = 0;                                  // the region eroded by kLookKeypointErosionPx
    double sharpFraction = NAN; // share of region pixels with sqrt(Gauss_3(h^2)) > 0.02, h = grey - Gauss_1(grey)
    double noiseFloor = NAN;    // 10th percentile of the std of h over unclipped 16 px blocks (both within the region)
    uint64_t noiseBlocks = 0;
    std::vector<double> spectrum; // mean radial power per 1-px frequency bin k = 0..32 (f = k / 64)
    std::vector<uint64_t> greyHistogram, saturationHistogram; // kLookHistogramBins bins over [0, 1] (pictures)
};

// The statistics of the pixels where `mask` (CV_8U, the image's size) is non-zero.
LookStatistics measureRegion(const LookImage& image, const cv::Mat& mask);

// Linear interpolation between order statistics (NumPy's default): q in [0, 1]; NaN for no values.
double percentileOf(std::vector<double> values, double q);

// Mean radial power of 64x64 Hann windows (stride 32) entirely inside `mask`, per frequency bin k = 0..32, and
// the windows used; a zero-window result is all NaN.
inline constexpr int kLookWindowPx = 64;
std::vector<double> radialSpectrum(const cv::Mat& centredGrey, const cv::Mat& mask, uint64_t& windows);
// Least-squares slope of log10 power against log10 f over the bins with f = k / 64 in [lo, hi]; NaN without two.
double spectrumSlope(const std::vector<double>& spectrum, double lo, double hi);

} // namespace sward
