#include "eval/pictures.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "eval/number_format.h"
#include "io/disparity_files.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

namespace {

// Plot geometry in pixels, and the mapping from (error, density) to canvas coordinates.
struct PlotFrame {
    static constexpr int W = 720, H = 400, left = 70, right = 20, top = 40, bottom = 50;
    double range = 4; // errors shown: [-range, range) px
    double yMax = 1e-9;
    int px(double e) const { return left + int(std::lround((e + range) / (2 * range) * (W - left - right))); }
    int py(double v) const { return H - bottom - int(std::lround(v / yMax * (H - top - bottom))); }
};

constexpr int kPlotBins = 64;

// The smallest power of two (4..256 px) that holds the A95 of every curve.
double plotRange(const std::vector<Curve>& curves) {
    double range = 4;
    for (const Curve& c : curves) {
        StereoMetrics m = c.accumulator->metrics();
        while (std::isfinite(m.accuracy[2]) && range < m.accuracy[2] && range < ErrorAccumulator::kSignedRange)
            range *= 2;
    }
    return range;
}

struct CurveDensity {
    std::vector<double> density; // per plot bin: fraction of estimated pixels per px of error
    double outside = 0;          // fraction of estimated pixels outside [-range, range)
};

// `binWidth` is a multiple of the 1/8 px accumulator bins, so each accumulator bin falls in one plot bin.
CurveDensity binnedDensity(const ErrorAccumulator& accumulator, double range, double binWidth) {
    CurveDensity result;
    result.density.assign(kPlotBins, 0.0);
    const std::vector<uint64_t>& hist = accumulator.signedHistogram();
    const double n = double(accumulator.estimatedPixels());
    uint64_t out = 0;
    for (size_t i = 0; i < hist.size(); ++i) {
        const double low = ErrorAccumulator::signedBinLow(i);
        if (low < -range || low >= range) {
            out += hist[i];
            continue;
        }
        result.density[size_t((low + range) / binWidth)] += double(hist[i]);
    }
    for (double& v : result.density) v = n > 0 ? v / n / binWidth : 0.0;
    result.outside = n > 0 ? double(out) / n : 0.0;
    return result;
}

void drawAxes(cv::Mat& canvas, const PlotFrame& f, const std::string& title) {
    const int W = PlotFrame::W, H = PlotFrame::H, left = PlotFrame::left, right = PlotFrame::right;
    const int top = PlotFrame::top, bottom = PlotFrame::bottom;
    const cv::Scalar black(0, 0, 0), grey(200, 200, 200);
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    for (int k = -4; k <= 4; ++k) {
        const double e = f.range * k / 4;
        cv::line(canvas, {f.px(e), top}, {f.px(e), H - bottom}, k == 0 ? cv::Scalar(150, 150, 150) : grey, 1);
        std::string label = fixed(e, f.range >= 16 ? 0 : 1);
        cv::putText(canvas, label, {f.px(e) - 12, H - bottom + 18}, font, 0.4, black, 1, cv::LINE_AA);
    }
    for (int k = 0; k <= 4; ++k) {
        const double v = f.yMax / 1.08 * k / 4;
        cv::line(canvas, {left, f.py(v)}, {W - right, f.py(v)}, grey, 1);
        cv::putText(canvas, fixed(v, 3), {4, f.py(v) + 4}, font, 0.4, black, 1, cv::LINE_AA);
    }
    cv::rectangle(canvas, {left, top}, {W - right, H - bottom}, black, 1);
    cv::putText(canvas, title + "  (y: fraction of estimated pixels per px of error)", {left, 24}, font, 0.45, black, 1,
                cv::LINE_AA);
    cv::putText(canvas, "signed error e = estimate - truth (px)", {left + 180, H - 12}, font, 0.45, black, 1,
                cv::LINE_AA);
}

// A step curve over the plot bins and its legend line (`index`: the curve's place in the legend).
void drawCurve(cv::Mat& canvas, const PlotFrame& f, const Curve& curve, const CurveDensity& d, size_t index,
               double binWidth) {
    std::vector<cv::Point> points;
    for (int b = 0; b < kPlotBins; ++b) {
        const double e0 = -f.range + b * binWidth;
        points.push_back({f.px(e0), f.py(d.density[b])});
        points.push_back({f.px(e0 + binWidth), f.py(d.density[b])});
    }
    cv::polylines(canvas, points, false, curve.colour, 2, cv::LINE_AA);
    const int right = PlotFrame::W - PlotFrame::right;
    const int ly = PlotFrame::top + 16 + int(index) * 18;
    cv::line(canvas, {right - 250, ly - 4}, {right - 225, ly - 4}, curve.colour, 2);
    cv::putText(canvas, curve.label + " (" + fixed(100 * d.outside, 1) + " % outside)", {right - 220, ly},
                cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

} // namespace

void writePng(const std::string& path, const cv::Mat& image) {
    std::vector<uint8_t> bytes;
    require(cv::imencode(".png", image, bytes), "cannot write '" + path + "': PNG encoding failed");
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

cv::Mat colourValues(std::span<const float> values, uint32_t width, uint32_t height, double lo, double hi,
                     bool (*valid)(float)) {
    cv::Mat level(int(height), int(width), CV_8UC1);
    const double scale = 255.0 / std::max(hi - lo, 1e-6);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float v = values[size_t(y) * width + x];
            const double scaled = valid(v) ? std::round((v - lo) * scale) : 0.0;
            level.at<uint8_t>(int(y), int(x)) = uint8_t(std::clamp(scaled, 0.0, 255.0));
        }
    cv::Mat colour;
    cv::applyColorMap(level, colour, cv::COLORMAP_TURBO);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            if (!valid(values[size_t(y) * width + x])) colour.at<cv::Vec3b>(int(y), int(x)) = {0, 0, 0};
    return colour;
}

cv::Mat colourDisparity(const std::vector<float>& d, uint32_t width, uint32_t height, double lo, double hi) {
    return colourValues(d, width, height, lo, hi, isValidDisparity);
}

cv::Mat differenceImage(const std::vector<float>& estimate, const std::vector<float>& truth, uint32_t width,
                        uint32_t height) {
    cv::Mat difference(int(height), int(width), CV_8UC1, cv::Scalar(0));
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            if (isValidDisparity(truth[i]) && isValidDisparity(estimate[i]))
                difference.at<uint8_t>(int(y), int(x)) = signedDifference8(double(estimate[i]) - double(truth[i]));
        }
    return difference;
}

void plotHistograms(const std::string& path, const std::string& title, const std::vector<Curve>& curves) {
    PlotFrame frame;
    frame.range = plotRange(curves);
    const double binWidth = 2 * frame.range / kPlotBins;
    std::vector<CurveDensity> densities;
    for (const Curve& c : curves) {
        densities.push_back(binnedDensity(*c.accumulator, frame.range, binWidth));
        for (double v : densities.back().density) frame.yMax = std::max(frame.yMax, v);
    }
    frame.yMax *= 1.08;
    cv::Mat canvas(PlotFrame::H, PlotFrame::W, CV_8UC3, cv::Scalar(255, 255, 255));
    drawAxes(canvas, frame, title);
    for (size_t c = 0; c < curves.size(); ++c) drawCurve(canvas, frame, curves[c], densities[c], c, binWidth);
    writePng(path, canvas);
}

namespace {

// The Middlebury colour wheel (Baker et al. 2011, flowToColor): 55 hues in six ramps, red -> yellow -> green ->
// cyan -> blue -> magenta -> red, so every flow benchmark's pictures read the same way.
std::vector<cv::Vec3d> middleburyColourWheel() {
    const int ramps[6] = {15, 6, 4, 11, 13, 6}; // RY, YG, GC, CB, BM, MR
    std::vector<cv::Vec3d> wheel;               // RGB, 0..255
    for (int i = 0; i < ramps[0]; ++i) wheel.push_back({255, 255.0 * i / ramps[0], 0});
    for (int i = 0; i < ramps[1]; ++i) wheel.push_back({255 - 255.0 * i / ramps[1], 255, 0});
    for (int i = 0; i < ramps[2]; ++i) wheel.push_back({0, 255, 255.0 * i / ramps[2]});
    for (int i = 0; i < ramps[3]; ++i) wheel.push_back({0, 255 - 255.0 * i / ramps[3], 255});
    for (int i = 0; i < ramps[4]; ++i) wheel.push_back({255.0 * i / ramps[4], 0, 255});
    for (int i = 0; i < ramps[5]; ++i) wheel.push_back({255, 0, 255 - 255.0 * i / ramps[5]});
    return wheel;
}

// The wheel's colour of a flow vector already divided by the picture's maximum magnitude (BGR).
cv::Vec3b wheelColour(const std::vector<cv::Vec3d>& wheel, double fx, double fy) {
    const double radius = std::sqrt(fx * fx + fy * fy);
    const double angle = std::atan2(-fy, -fx) / std::numbers::pi;
    const double fk = (angle + 1.0) / 2.0 * double(wheel.size() - 1);
    const size_t k0 = size_t(fk), k1 = (k0 + 1) % wheel.size();
    const double f = fk - double(k0);
    cv::Vec3b bgr;
    for (int c = 0; c < 3; ++c) {
        double col = ((1 - f) * wheel[k0][c] + f * wheel[k1][c]) / 255.0;
        col = radius <= 1 ? 1 - radius * (1 - col) : col * 0.75; // saturation grows with speed; beyond: darker
        bgr[2 - c] = uint8_t(std::clamp(255.0 * col, 0.0, 255.0));
    }
    return bgr;
}

} // namespace

cv::Mat colourFlow(const FlowField& flow, double maxMagnitude) {
    static const std::vector<cv::Vec3d> wheel = middleburyColourWheel();
    cv::Mat colour(int(flow.height), int(flow.width), CV_8UC3, cv::Scalar(0, 0, 0));
    const double scale = 1.0 / std::max(maxMagnitude, 1e-6);
    for (uint32_t y = 0; y < flow.height; ++y)
        for (uint32_t x = 0; x < flow.width; ++x) {
            const size_t i = size_t(y) * flow.width + x;
            if (isValidFlow(flow.u(i), flow.v(i)))
                colour.at<cv::Vec3b>(int(y), int(x)) = wheelColour(wheel, flow.u(i) * scale, flow.v(i) * scale);
        }
    return colour;
}

} // namespace sward
