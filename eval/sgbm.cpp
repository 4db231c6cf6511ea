#include "eval/sgbm.h"

#include "common/error.h"

#include <opencv2/calib3d.hpp>

namespace sward {

namespace {

int openCvMode(SgbmMode mode) {
    switch (mode) {
    case SgbmMode::Sgbm:
        return cv::StereoSGBM::MODE_SGBM;
    case SgbmMode::HH:
        return cv::StereoSGBM::MODE_HH;
    case SgbmMode::ThreeWay:
        return cv::StereoSGBM::MODE_SGBM_3WAY;
    case SgbmMode::HH4:
        return cv::StereoSGBM::MODE_HH4;
    }
    return cv::StereoSGBM::MODE_SGBM;
}

} // namespace

SgbmMode parseSgbmMode(const std::string& text) {
    if (text == "sgbm") return SgbmMode::Sgbm;
    if (text == "hh") return SgbmMode::HH;
    if (text == "3way") return SgbmMode::ThreeWay;
    if (text == "hh4") return SgbmMode::HH4;
    throw Error("unknown SGBM mode '" + text + "' (expected sgbm, hh, 3way or hh4)");
}

const char* sgbmModeName(SgbmMode mode) {
    switch (mode) {
    case SgbmMode::Sgbm:
        return "sgbm";
    case SgbmMode::HH:
        return "hh";
    case SgbmMode::ThreeWay:
        return "3way";
    case SgbmMode::HH4:
        return "hh4";
    }
    return "?";
}

ResolvedSgbm resolveSgbm(const SgbmOptions& options, const StereoCalib& calib, uint32_t width) {
    ResolvedSgbm r;
    r.options = options;
    r.channels = options.gray ? 1 : 3;
    const int ws = options.blockSize;
    require(ws >= 1 && ws <= 31 && ws % 2 == 1, "SGBM block size must be odd and in 1..31, got " + std::to_string(ws));
    r.numDisparities = options.numDisparities ? *options.numDisparities : int((calib.ndisp + 15) / 16 * 16);
    require(r.numDisparities > 0 && r.numDisparities % 16 == 0,
            "SGBM numDisparities must be a positive multiple of 16, got " + std::to_string(r.numDisparities));
    require(uint32_t(r.numDisparities) < width, "SGBM numDisparities " + std::to_string(r.numDisparities) +
                                                    " must be smaller than the image width " + std::to_string(width));
    r.p1 = options.p1 ? *options.p1 : 8 * r.channels * ws * ws;
    r.p2 = options.p2 ? *options.p2 : 32 * r.channels * ws * ws;
    require(r.p1 > 0 && r.p2 > r.p1,
            "SGBM needs 0 < P1 < P2, got P1 " + std::to_string(r.p1) + ", P2 " + std::to_string(r.p2));
    require(options.uniquenessRatio >= 0 && options.speckleWindowSize >= 0 && options.speckleRange >= 0,
            "SGBM uniqueness, speckle window and speckle range must not be negative");
    return r;
}

std::string sgbmDescription(const ResolvedSgbm& s) {
    return std::string("OpenCV StereoSGBM: mode ") + sgbmModeName(s.options.mode) + ", " +
           (s.options.gray ? "grey" : "colour") + " (cn " + std::to_string(s.channels) + "), block size " +
           std::to_string(s.options.blockSize) + ", P1 " + std::to_string(s.p1) + ", P2 " + std::to_string(s.p2) +
           ", minDisparity 0, numDisparities " + std::to_string(s.numDisparities) + ", uniqueness " +
           std::to_string(s.options.uniquenessRatio) + " %, speckle window " +
           std::to_string(s.options.speckleWindowSize) + " range " + std::to_string(s.options.speckleRange) +
           ", disp12MaxDiff " + std::to_string(s.options.disp12MaxDiff);
}

std::vector<float> runSgbm(const ResolvedSgbm& r, uint32_t width, uint32_t height, std::span<const uint8_t> left,
                           std::span<const uint8_t> right) {
    const size_t expected = size_t(width) * height * r.channels;
    require(left.size() == expected && right.size() == expected, "SGBM input images must be " + std::to_string(width) +
                                                                     "x" + std::to_string(height) + " with " +
                                                                     std::to_string(r.channels) + " channel(s)");
    const int type = r.channels == 1 ? CV_8UC1 : CV_8UC3;
    // OpenCV only reads the inputs; the const_cast wraps the caller's pixels without a copy.
    cv::Mat l(int(height), int(width), type, const_cast<uint8_t*>(left.data()));
    cv::Mat rr(int(height), int(width), type, const_cast<uint8_t*>(right.data()));
    cv::Ptr<cv::StereoSGBM> sgbm = cv::StereoSGBM::create(
        0, r.numDisparities, r.options.blockSize, r.p1, r.p2, r.options.disp12MaxDiff, 0, r.options.uniquenessRatio,
        r.options.speckleWindowSize, r.options.speckleRange, openCvMode(r.options.mode));
    cv::Mat fixedPoint;
    sgbm->compute(l, rr, fixedPoint);
    require(fixedPoint.type() == CV_16SC1, "SGBM returned an unexpected image type");
    // Disparity * 16 in fixed point; minDisparity - 1 (here -1 * 16) marks pixels without a match. A disparity of
    // exactly 0 also counts as "no value", as in KITTI's format, so every matcher is judged by the same rule.
    std::vector<float> d(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y) {
        const int16_t* row = fixedPoint.ptr<int16_t>(int(y));
        for (uint32_t x = 0; x < width; ++x) d[size_t(y) * width + x] = row[x] > 0 ? float(row[x]) / 16.0f : 0.0f;
    }
    return d;
}

} // namespace sward
