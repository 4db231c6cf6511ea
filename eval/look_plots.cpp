// The realism instrument's pictures (eval/look_report.h): per region, three panels drawn with OpenCV: the grey and
// saturation histograms (share of pixels per 1/64 bin, pooled over the images) and the radial power spectrum
// (pooled over every window, log10 power against log10 frequency), sward in red, the real images in blue.
#include "eval/look_report.h"

#include "eval/pictures.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sward {

namespace {

constexpr int kPanelWidth = 320, kPanelHeight = 240, kMargin = 36;
const cv::Scalar kSwardColour(40, 40, 220), kRealColour(200, 120, 30), kAxisColour(90, 90, 90);

struct Pooled {
    std::vector<double> grey, saturation, spectrum; // shares; mean power
    bool any = false;
};

Pooled pool(const std::vector<LookImageResult>& images, const std::string& region) {
    Pooled p;
    p.grey.assign(kLookHistogramBins, 0);
    p.saturation.assign(kLookHistogramBins, 0);
    p.spectrum.assign(kLookWindowPx / 2 + 1, 0);
    double pixels = 0, windows = 0;
    for (const LookImageResult& image : images)
        for (const auto& [name, s] : image.regions) {
            if (name != region || s.pixels == 0) continue;
            for (int b = 0; b < kLookHistogramBins; ++b) {
                p.grey[size_t(b)] += double(s.greyHistogram[size_t(b)]);
                p.saturation[size_t(b)] += double(s.saturationHistogram[size_t(b)]);
            }
            pixels += double(s.pixels);
            if (s.spectrumWindows > 0)
                for (size_t k = 0; k < p.spectrum.size(); ++k)
                    p.spectrum[k] += s.spectrum[k] * double(s.spectrumWindows);
            windows += double(s.spectrumWindows);
        }
    p.any = pixels > 0;
    for (double& v : p.grey) v /= std::max(pixels, 1.0);
    for (double& v : p.saturation) v /= std::max(pixels, 1.0);
    for (double& v : p.spectrum) v = windows > 0 ? v / windows : NAN;
    return p;
}

// A panel's frame and labels; returns the plotting rectangle.
cv::Rect drawPanel(cv::Mat& canvas, int column, const std::string& title, const std::string& xLabel) {
    const cv::Rect plot(column * kPanelWidth + kMargin, kMargin / 2 + 14, kPanelWidth - kMargin - 10,
                        kPanelHeight - kMargin - 28);
    cv::rectangle(canvas, plot, kAxisColour, 1);
    cv::putText(canvas, title, {column * kPanelWidth + kMargin, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1,
                cv::LINE_AA);
    cv::putText(canvas, xLabel, {plot.x, plot.y + plot.height + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.38, kAxisColour, 1,
                cv::LINE_AA);
    return plot;
}

// Polyline of (x, y) in [0, 1]^2 (y up) inside `plot`; non-finite points break the line.
void drawCurve(cv::Mat& canvas, const cv::Rect& plot, const std::vector<cv::Point2d>& points, const cv::Scalar& c) {
    for (size_t i = 1; i < points.size(); ++i) {
        const cv::Point2d a = points[i - 1], b = points[i];
        if (!std::isfinite(a.y) || !std::isfinite(b.y)) continue;
        auto at = [&](cv::Point2d p) {
            return cv::Point(plot.x + int(std::lround(std::clamp(p.x, 0.0, 1.0) * plot.width)),
                             plot.y + plot.height - int(std::lround(std::clamp(p.y, 0.0, 1.0) * plot.height)));
        };
        cv::line(canvas, at(a), at(b), c, 2, cv::LINE_AA);
    }
}

void drawHistogram(cv::Mat& canvas, int column, const char* title, const Pooled& sward, const Pooled& real,
                   bool histogramOfGrey) {
    const cv::Rect plot = drawPanel(canvas, column, title, "0 .. 1");
    const std::vector<double>& a = histogramOfGrey ? sward.grey : sward.saturation;
    const std::vector<double>& b = histogramOfGrey ? real.grey : real.saturation;
    double top = 1e-9;
    for (double v : a) top = std::max(top, v);
    if (real.any)
        for (double v : b) top = std::max(top, v);
    auto curve = [&](const std::vector<double>& h) {
        std::vector<cv::Point2d> points;
        for (size_t i = 0; i < h.size(); ++i) points.push_back({(double(i) + 0.5) / double(h.size()), h[i] / top});
        return points;
    };
    drawCurve(canvas, plot, curve(a), kSwardColour);
    if (real.any) drawCurve(canvas, plot, curve(b), kRealColour);
}

void drawSpectrum(cv::Mat& canvas, const Pooled& sward, const Pooled& real) {
    const cv::Rect plot = drawPanel(canvas, 2, "radial power (log-log)", "f = 1/64 .. 1/2 cycles/px");
    double lo = INFINITY, hi = -INFINITY;
    for (const Pooled* p : {&sward, &real})
        for (size_t k = 1; k < p->spectrum.size(); ++k)
            if (p->spectrum[k] > 0)
                lo = std::min(lo, std::log10(p->spectrum[k])), hi = std::max(hi, std::log10(p->spectrum[k]));
    if (!(hi > lo)) return;
    auto curve = [&](const std::vector<double>& s) {
        std::vector<cv::Point2d> points;
        for (size_t k = 1; k < s.size(); ++k)
            points.push_back({std::log10(double(k)) / std::log10(double(s.size() - 1)),
                              s[k] > 0 ? (std::log10(s[k]) - lo) / (hi - lo) : NAN});
        return points;
    };
    drawCurve(canvas, plot, curve(sward.spectrum), kSwardColour);
    if (real.any) drawCurve(canvas, plot, curve(real.spectrum), kRealColour);
    char range[64];
    std::snprintf(range, sizeof range, "power 1e%.1f .. 1e%.1f", lo, hi);
    cv::putText(canvas, range, {plot.x + 4, plot.y + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.35, kAxisColour, 1, cv::LINE_AA);
}

} // namespace

std::vector<std::string> lookPictureRegions(const LookResult& result) {
    std::vector<std::string> regions;
    for (const std::string& region : result.regionOrder)
        if (result.sward.contains(region)) regions.push_back(region);
    return regions;
}

void writeLookPictures(const LookResult& result, const std::string& outDir) {
    for (const std::string& region : lookPictureRegions(result)) {
        const Pooled sward = pool(result.frames, region), real = pool(result.reference, region);
        cv::Mat canvas(kPanelHeight, 3 * kPanelWidth, CV_8UC3, cv::Scalar(255, 255, 255));
        drawHistogram(canvas, 0, ("grey, region " + region).c_str(), sward, real, true);
        drawHistogram(canvas, 1, "HSV saturation", sward, real, false);
        drawSpectrum(canvas, sward, real);
        cv::putText(canvas, "sward", {3 * kPanelWidth - 110, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kSwardColour, 1,
                    cv::LINE_AA);
        if (real.any)
            cv::putText(canvas, "real", {3 * kPanelWidth - 50, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kRealColour, 1,
                        cv::LINE_AA);
        writePng(outDir + "/look_" + region + ".png", canvas);
    }
}

} // namespace sward
