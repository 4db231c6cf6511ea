// The spectrum statistics of eval/look_statistics.h: radially averaged power of Hann-windowed 64x64 windows and
// the log-log slope fitted to it.
#include "eval/look_statistics.h"

#include <opencv2/core.hpp>

#include <cmath>
#include <numbers>

namespace sward {

namespace {

constexpr int kBins = kLookWindowPx / 2 + 1; // k = 0 .. 32: f = k / 64 cycles / px up to Nyquist

// The periodic Hann window's outer product, normalised so that white noise of variance v has power v in every
// frequency cell.
cv::Mat hannWindow() {
    const int n = kLookWindowPx;
    std::vector<double> w(size_t(n), 0.0);
    for (int i = 0; i < n; ++i) w[size_t(i)] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / n);
    cv::Mat window(n, n, CV_64F);
    double squares = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            window.at<double>(y, x) = w[size_t(y)] * w[size_t(x)];
            squares += window.at<double>(y, x) * window.at<double>(y, x);
        }
    return window / std::sqrt(squares);
}

// The frequency bin of each DFT cell: the rounded radius in cycles per window; kBins where it is beyond Nyquist.
std::vector<int> cellBins() {
    const int n = kLookWindowPx;
    std::vector<int> bins(size_t(n * n));
    for (int v = 0; v < n; ++v)
        for (int u = 0; u < n; ++u) {
            const int fx = u <= n / 2 ? u : u - n, fy = v <= n / 2 ? v : v - n;
            const long k = std::lround(std::sqrt(double(fx * fx + fy * fy)));
            bins[size_t(v * n + u)] = k < kBins ? int(k) : kBins;
        }
    return bins;
}

bool insideMask(const cv::Mat& mask, const cv::Rect& r) {
    for (int y = r.y; y < r.y + r.height; ++y) {
        const uint8_t* row = mask.ptr<uint8_t>(y);
        for (int x = r.x; x < r.x + r.width; ++x)
            if (!row[x]) return false;
    }
    return true;
}

} // namespace

std::vector<double> radialSpectrum(const cv::Mat& centredGrey, const cv::Mat& mask, uint64_t& windows) {
    static const cv::Mat window = hannWindow();
    static const std::vector<int> bins = cellBins();
    const int n = kLookWindowPx, stride = n / 2;
    std::vector<double> sum(size_t(kBins), 0.0);
    std::vector<uint64_t> cells(size_t(kBins), 0);
    for (int k : bins)
        if (k < kBins) ++cells[size_t(k)];
    windows = 0;
    for (int y = 0; y + n <= centredGrey.rows; y += stride)
        for (int x = 0; x + n <= centredGrey.cols; x += stride) {
            const cv::Rect r(x, y, n, n);
            if (!insideMask(mask, r)) continue;
            cv::Mat patch;
            centredGrey(r).convertTo(patch, CV_64F);
            patch -= cv::mean(patch)[0];
            cv::Mat spectrum;
            cv::dft(patch.mul(window), spectrum, cv::DFT_COMPLEX_OUTPUT);
            for (int i = 0; i < n * n; ++i) {
                const int k = bins[size_t(i)];
                if (k == kBins) continue;
                const cv::Vec2d c = spectrum.at<cv::Vec2d>(i / n, i % n);
                sum[size_t(k)] += c[0] * c[0] + c[1] * c[1];
            }
            ++windows;
        }
    std::vector<double> power(size_t(kBins), NAN);
    if (windows == 0) return power;
    for (int k = 0; k < kBins; ++k) power[size_t(k)] = sum[size_t(k)] / double(cells[size_t(k)] * windows);
    return power;
}

double spectrumSlope(const std::vector<double>& spectrum, double lo, double hi) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t k = 1; k < spectrum.size(); ++k) {
        const double f = double(k) / kLookWindowPx;
        if (f < lo - 1e-12 || f > hi + 1e-12 || !(spectrum[k] > 0)) continue;
        const double x = std::log10(f), y = std::log10(spectrum[k]);
        n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double denominator = n * sxx - sx * sx;
    if (n < 2 || denominator <= 0) return NAN;
    return (n * sxy - sx * sy) / denominator;
}

} // namespace sward
