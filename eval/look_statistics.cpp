#include "eval/look_statistics.h"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

namespace {

// Gaussian kernels of radius ceil(3 sigma), reflected borders (BORDER_REFLECT_101) everywhere.
cv::Mat gauss(const cv::Mat& image, double sigma) {
    const int size = 2 * int(std::ceil(3 * sigma)) + 1;
    cv::Mat out;
    cv::GaussianBlur(image, out, cv::Size(size, size), sigma, sigma, cv::BORDER_REFLECT_101);
    return out;
}

// HSV of one pixel's R, G, B in [0, 1]: hue in degrees, saturation (max - min) / max, value max.
struct Hsv {
    double h, s, v;
};
Hsv toHsv(double r, double g, double b) {
    const double max = std::max({r, g, b}), min = std::min({r, g, b}), d = max - min;
    Hsv out{0, max > 0 ? d / max : 0, max};
    if (d > 0) {
        if (max == r)
            out.h = 60 * (g - b) / d;
        else if (max == g)
            out.h = 60 * (b - r) / d + 120;
        else
            out.h = 60 * (r - g) / d + 240;
        if (out.h < 0) out.h += 360;
    }
    return out;
}

std::vector<cv::Point2f> detect(const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& grey8) {
    std::vector<cv::KeyPoint> keypoints;
    detector->detect(grey8, keypoints);
    std::vector<cv::Point2f> points;
    points.reserve(keypoints.size());
    for (const cv::KeyPoint& k : keypoints) points.push_back(k.pt);
    return points;
}

// Mean and population std of `values` where `mask` is set, from sums of the differences to the first such value
// (double, raster order): equal values give exactly their value and a std of exactly 0.
struct Moments {
    uint64_t n = 0;
    double mean = NAN, std = NAN;
};
template <class T> Moments momentsOf(const cv::Mat& values, const cv::Mat& mask) {
    Moments m;
    double shift = 0, sum = 0, squares = 0;
    for (int y = 0; y < values.rows; ++y)
        for (int x = 0; x < values.cols; ++x) {
            if (!mask.at<uint8_t>(y, x)) continue;
            if (m.n++ == 0) shift = double(values.at<T>(y, x));
            const double d = double(values.at<T>(y, x)) - shift;
            sum += d, squares += d * d;
        }
    if (m.n == 0) return m;
    const double meanDifference = sum / double(m.n);
    m.mean = shift + meanDifference;
    m.std = std::sqrt(std::max(0.0, squares / double(m.n) - meanDifference * meanDifference));
    return m;
}

void measureHistograms(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    s.greyHistogram.assign(kLookHistogramBins, 0);
    s.saturationHistogram.assign(kLookHistogramBins, 0);
    auto bin = [](double v) { return size_t(std::clamp(int(v * kLookHistogramBins), 0, kLookHistogramBins - 1)); };
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (mask.at<uint8_t>(y, x)) {
                ++s.greyHistogram[bin(image.grey.at<float>(y, x))];
                ++s.saturationHistogram[bin(image.saturation.at<double>(y, x))];
            }
}

void measureColour(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    measureHistograms(image, mask, s);
    s.saturationMean = momentsOf<double>(image.saturation, mask).mean;
    s.valueStd = momentsOf<double>(image.value, mask).std;
    double c = 0, sn = 0, w = 0;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x) {
            if (!mask.at<uint8_t>(y, x)) continue;
            const double weight = image.saturation.at<double>(y, x);
            const double angle = image.hue.at<double>(y, x) * std::numbers::pi / 180;
            c += weight * std::cos(angle), sn += weight * std::sin(angle), w += weight;
        }
    if (w <= 0) return; // no saturated pixel: hue undefined
    const double r = std::min(1.0, std::hypot(c, sn) / w);
    s.hueStdDegrees = r > 0 ? std::sqrt(-2 * std::log(r)) * 180 / std::numbers::pi : INFINITY;
}

// Sobel / 8 on the grey, at region pixels whose 3x3 neighbourhood lies inside the frame.
void measureGradients(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    const cv::Mat &dx = image.dx, &dy = image.dy;
    cv::Mat inner = cv::Mat::zeros(mask.size(), CV_8U);
    if (mask.rows > 2 && mask.cols > 2)
        mask(cv::Rect(1, 1, mask.cols - 2, mask.rows - 2)).copyTo(inner(cv::Rect(1, 1, mask.cols - 2, mask.rows - 2)));
    std::vector<double> magnitudes;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (inner.at<uint8_t>(y, x)) magnitudes.push_back(std::hypot(dx.at<double>(y, x), dy.at<double>(y, x)));
    if (magnitudes.empty()) return;
    double sum = 0;
    for (double m : magnitudes) sum += m;
    s.gradientMean = sum / double(magnitudes.size());
    s.gradientP99 = percentileOf(std::move(magnitudes), 0.99);
    const Moments m = momentsOf<double>(dx, inner);
    if (!(m.std >= kLookGreyConstantStd)) return;
    double fourth = 0;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (inner.at<uint8_t>(y, x)) fourth += std::pow((dx.at<double>(y, x) - m.mean) / m.std, 4);
    s.dxKurtosis = fourth / double(m.n) - 3;
}

// The next level's mask: a pixel is in the region when every pixel of its 2x2 block (those inside the finer
// level) is.
cv::Mat downsampleMask(const cv::Mat& mask, cv::Size size) {
    cv::Mat out(size, CV_8U);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            bool all = true;
            for (int v = 2 * y; v < std::min(2 * y + 2, mask.rows); ++v)
                for (int u = 2 * x; u < std::min(2 * x + 2, mask.cols); ++u) all = all && mask.at<uint8_t>(v, u);
            out.at<uint8_t>(y, x) = all ? 255 : 0;
        }
    return out;
}

// The RMS of each Laplacian level over the region's pixels at that level, divided by the region's mean grey.
void measureLaplacian(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    cv::Mat m = mask;
    for (size_t k = 0; k < image.laplacian.size(); ++k) {
        const cv::Mat& band = image.laplacian[k];
        if (k > 0) m = downsampleMask(m, band.size());
        double squares = 0;
        uint64_t n = 0;
        for (int y = 0; y < band.rows; ++y)
            for (int x = 0; x < band.cols; ++x)
                if (m.at<uint8_t>(y, x)) squares += double(band.at<float>(y, x)) * band.at<float>(y, x), ++n;
        if (n > 0 && s.greyMean > 0) s.laplacianRms[k] = std::sqrt(squares / double(n)) / s.greyMean;
    }
}

// Keypoints of the whole frame whose pixel (rounded position) lies in the region eroded by 8 px (a disc; outside
// the frame counts as outside the region), per megapixel of the eroded area.
void measureKeypoints(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    const int size = 2 * kLookKeypointErosionPx + 1;
    cv::Mat eroded;
    cv::erode(mask, eroded, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size)), cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT, cv::Scalar(0));
    s.erodedPixels = uint64_t(cv::countNonZero(eroded));
    if (s.erodedPixels == 0) return;
    for (size_t d = 0; d < image.keypoints.size(); ++d) {
        uint64_t count = 0;
        for (const cv::Point2f& p : image.keypoints[d]) {
            const int x = std::clamp(int(std::lround(p.x)), 0, eroded.cols - 1);
            const int y = std::clamp(int(std::lround(p.y)), 0, eroded.rows - 1);
            count += eroded.at<uint8_t>(y, x) != 0;
        }
        s.keypointsPerMegapixel[d] = double(count) / (double(s.erodedPixels) * 1e-6);
    }
}

// The region's own texture: every Gaussian is a normalised convolution over the region (Gauss(v m) / Gauss(m), m
// the mask in {0, 1}), so a smooth gap between textured plants stays smooth. h = grey - Gauss_1(grey); sharp-texture
// fraction: sqrt(Gauss_3(h^2)) > 0.02 at region pixels. Noise floor: 16 px blocks from the frame's corner, entirely
// inside the region and with no clipped pixel; 10th percentile of their std of h.
void measureTexture(const LookImage& image, const cv::Mat& mask, LookStatistics& s) {
    cv::Mat m;
    mask.convertTo(m, CV_32F, 1.0 / 255);
    // Far outside the region the normalised blur is 0 / 0: h is set to 0 there, so it never enters a sum.
    cv::Mat h = image.centred - gauss(image.centred.mul(m), 1) / gauss(m, 1);
    h.setTo(0, mask == 0);
    const cv::Mat localRms = gauss(h.mul(h), 3) / gauss(m, 3);
    uint64_t sharp = 0;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (mask.at<uint8_t>(y, x)) sharp += std::sqrt(double(localRms.at<float>(y, x))) > kLookSharpThreshold;
    if (s.pixels > 0) s.sharpFraction = double(sharp) / double(s.pixels);
    std::vector<double> stds;
    const int b = kLookNoiseBlockPx;
    for (int y = 0; y + b <= mask.rows; y += b)
        for (int x = 0; x + b <= mask.cols; x += b) {
            const cv::Rect block(x, y, b, b);
            if (cv::countNonZero(mask(block)) != b * b || cv::countNonZero(image.clipped(block)) != 0) continue;
            stds.push_back(momentsOf<float>(h(block), cv::Mat(b, b, CV_8U, cv::Scalar(255))).std);
        }
    s.noiseBlocks = stds.size();
    s.noiseFloor = percentileOf(std::move(stds), kLookNoisePercentile);
}

} // namespace

double percentileOf(std::vector<double> values, double q) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const double position = q * double(values.size() - 1);
    const size_t below = size_t(std::floor(position));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - double(below)) * (values[above] - values[below]);
}

LookImage prepareLookImage(const cv::Mat& bgr, bool detectKeypoints) {
    // HSV in double from the input's own values; the grey through OpenCV (which converts 32-bit floats only).
    const double scale = bgr.depth() == CV_8U ? 1.0 / 255 : 1.0;
    cv::Mat colour, colour32;
    bgr.convertTo(colour, CV_64FC3, scale);
    bgr.convertTo(colour32, CV_32FC3, scale);
    LookImage image;
    cv::cvtColor(colour32, image.grey, cv::COLOR_BGR2GRAY);
    image.hue.create(bgr.size(), CV_64F);
    image.saturation.create(bgr.size(), CV_64F);
    image.value.create(bgr.size(), CV_64F);
    image.clipped.create(bgr.size(), CV_8U);
    double sum = 0;
    for (int y = 0; y < bgr.rows; ++y)
        for (int x = 0; x < bgr.cols; ++x) {
            const cv::Vec3d c = colour.at<cv::Vec3d>(y, x);
            const Hsv hsv = toHsv(c[2], c[1], c[0]);
            image.hue.at<double>(y, x) = hsv.h;
            image.saturation.at<double>(y, x) = hsv.s;
            image.value.at<double>(y, x) = hsv.v;
            bool clipped = false;
            for (int i = 0; i < 3; ++i) clipped = clipped || c[i] <= 0 || c[i] >= 1;
            image.clipped.at<uint8_t>(y, x) = clipped ? 255 : 0;
            sum += image.grey.at<float>(y, x);
        }
    image.centred = image.grey - float(sum / double(bgr.total()));
    cv::Sobel(image.centred, image.dx, CV_64F, 1, 0, 3, 1.0 / 8, 0, cv::BORDER_REFLECT_101);
    cv::Sobel(image.centred, image.dy, CV_64F, 0, 1, 3, 1.0 / 8, 0, cv::BORDER_REFLECT_101);
    // Level k = G_k - pyrUp(G_{k+1}), G_0 the centred grey, G_{k+1} = pyrDown(G_k); levels stop at a 1 px side.
    cv::Mat g = image.centred;
    for (int k = 0; k < kLookPyramidLevels && g.cols >= 2 && g.rows >= 2; ++k) {
        cv::Mat next, up;
        cv::pyrDown(g, next);
        cv::pyrUp(next, up, g.size());
        image.laplacian.push_back(g - up);
        g = next;
    }
    if (!detectKeypoints) return image;
    cv::Mat grey8;
    image.grey.convertTo(grey8, CV_8U, 255); // rounded, saturated
    image.keypoints[0] = detect(cv::ORB::create(kLookOrbFeatures), grey8);
    image.keypoints[1] = detect(cv::SIFT::create(), grey8);
    image.keypoints[2] = detect(cv::FastFeatureDetector::create(kLookFastThreshold, true), grey8);
    return image;
}

LookStatistics measureRegion(const LookImage& image, const cv::Mat& mask) {
    LookStatistics s;
    const Moments grey = momentsOf<float>(image.grey, mask);
    s.pixels = grey.n;
    s.greyMean = grey.mean;
    s.greyStd = grey.std;
    if (s.pixels == 0) return s;
    measureColour(image, mask, s);
    measureGradients(image, mask, s);
    measureLaplacian(image, mask, s);
    s.spectrum = radialSpectrum(image.centred, mask, s.spectrumWindows);
    s.spectrumSlope = spectrumSlope(s.spectrum, 2.0 / kLookWindowPx, 0.4);
    s.spectrumSlopeHigh = spectrumSlope(s.spectrum, 0.1, 0.4);
    measureKeypoints(image, mask, s);
    measureTexture(image, mask, s);
    return s;
}

} // namespace sward
