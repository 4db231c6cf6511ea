#include "eval/pictures.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "eval/number_format.h"
#include "io/disparity_files.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

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

cv::Mat colourDisparity(const std::vector<float>& d, uint32_t width, uint32_t height, double lo, double hi) {
    cv::Mat level(int(height), int(width), CV_8UC1);
    const double scale = 255.0 / std::max(hi - lo, 1e-6);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            float v = d[size_t(y) * width + x];
            level.at<uint8_t>(int(y), int(x)) = uint8_t(std::clamp(std::round((v - lo) * scale), 0.0, 255.0));
        }
    cv::Mat colour;
    cv::applyColorMap(level, colour, cv::COLORMAP_TURBO);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            if (!isValidDisparity(d[size_t(y) * width + x])) colour.at<cv::Vec3b>(int(y), int(x)) = {0, 0, 0};
    return colour;
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

} // namespace sward
