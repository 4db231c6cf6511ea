#include "eval/evaluation.h"

#include "common/error.h"
#include "io/image_io.h"

#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <thread>

namespace fs = std::filesystem;

namespace sward {

namespace {

std::string frameName(uint32_t frame) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06u", frame);
    return name;
}

bool isFile(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

void writePng(const std::string& path, const cv::Mat& image) {
    std::vector<uint8_t> bytes;
    require(cv::imencode(".png", image, bytes), "cannot write '" + path + "': PNG encoding failed");
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

void makeDirectory(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    require(!ec && fs::is_directory(dir), "cannot create report folder '" + dir +
                                              "': " + (ec ? ec.message() : std::string("a file of that name exists")));
}

// OpenCV parallelises some SGBM modes over image stripes; frames are our unit of parallelism instead, so its
// result can never depend on the thread count. Restores OpenCV's setting on exit.
struct SingleThreadedOpenCV {
    int previous = cv::getNumThreads();
    SingleThreadedOpenCV() { cv::setNumThreads(1); }
    ~SingleThreadedOpenCV() { cv::setNumThreads(previous); }
};

cv::Mat readView(const std::string& path, bool gray) {
    require(isFile(path), "missing image '" + path + "'");
    cv::Mat image = cv::imread(path, gray ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
    require(!image.empty() && image.depth() == CV_8U, "cannot decode image '" + path + "' as 8-bit PNG");
    return image;
}

// Semantic class groups (dataset contract: 1 ground, 2..5 vegetation categories, 8 objects, 9 felled, 10 cut).
constexpr const char* kClassNames[] = {"vegetation", "ground", "object", "other"};
size_t classGroup(uint8_t id) {
    if ((id >= 2 && id <= 5) || id == 9 || id == 10) return 0;
    if (id == 1) return 1;
    if (id == 8) return 2;
    return 3;
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

struct FrameWork {
    uint32_t frame = 0;
    ErrorAccumulator total;
    std::vector<ErrorAccumulator> classes;
    std::vector<ErrorAccumulator> bands;
    double matchSeconds = 0;
};

struct DatasetSetup {
    std::string dir, disparitiesDir, pictureDir;
    const EvaluationOptions* options = nullptr;
    StereoCalib calib;
    std::optional<ResolvedSgbm> sgbm;
    bool semantic = false;
    double colourLo = 0, colourHi = 1;
};

FrameWork evaluateFrame(const DatasetSetup& setup, uint32_t frame) {
    const std::string name = frameName(frame);
    FrameWork work;
    work.frame = frame;
    DisparityMap truth = readGroundTruth(setup.dir, frame);
    const uint32_t w = truth.width, h = truth.height;
    require(w == setup.calib.width && h == setup.calib.height,
            setup.dir + "/calib.txt says " + std::to_string(setup.calib.width) + "x" +
                std::to_string(setup.calib.height) + " but the ground truth of frame " + name + " is " +
                std::to_string(w) + "x" + std::to_string(h));

    std::vector<float> estimate;
    if (setup.sgbm) {
        const bool gray = setup.sgbm->options.gray;
        cv::Mat left = readView(setup.dir + "/preview/" + name + ".png", gray);
        cv::Mat right = readView(setup.dir + "/preview_right/" + name + ".png", gray);
        for (const cv::Mat* view : {&left, &right})
            require(view->cols == int(w) && view->rows == int(h),
                    setup.dir + ": preview images of frame " + name + " are " + std::to_string(view->cols) + "x" +
                        std::to_string(view->rows) + ", the ground truth " + std::to_string(w) + "x" +
                        std::to_string(h));
        auto start = std::chrono::steady_clock::now();
        estimate = runSgbm(*setup.sgbm, w, h, {left.data, left.total() * left.elemSize()},
                           {right.data, right.total() * right.elemSize()});
        work.matchSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (setup.options->saveDisparities) writePfm(setup.pictureDir + "/disparity/" + name + ".pfm", w, h, estimate);
    } else {
        std::string path = setup.disparitiesDir + "/" + name + ".pfm";
        if (!isFile(path)) path = setup.disparitiesDir + "/" + name + ".png";
        require(isFile(path), "no estimate for frame " + name + ": neither '" + setup.disparitiesDir + "/" + name +
                                  ".pfm' nor '" + path + "' exists");
        DisparityMap map = readDisparity(path);
        require(map.width == w && map.height == h, path + " is " + std::to_string(map.width) + "x" +
                                                       std::to_string(map.height) + ", the ground truth " +
                                                       std::to_string(w) + "x" + std::to_string(h));
        estimate = std::move(map.values);
    }

    cv::Mat semantic;
    if (setup.semantic) {
        const std::string path = setup.dir + "/semantic/" + name + ".png";
        require(isFile(path), "missing semantic image '" + path + "'");
        semantic = cv::imread(path, cv::IMREAD_UNCHANGED);
        require(!semantic.empty() && semantic.type() == CV_8UC1 && semantic.cols == int(w) && semantic.rows == int(h),
                path + ": expected an 8-bit one-channel class image of " + std::to_string(w) + "x" + std::to_string(h));
        work.classes.resize(std::size(kClassNames));
    }
    const std::vector<double>& edges = setup.options->bandEdgesMetres;
    work.bands.resize(edges.size() + 1);

    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const float gt = truth.values[i];
            if (!isValidDisparity(gt)) continue;
            work.total.add(estimate[i], gt);
            if (setup.semantic) work.classes[classGroup(semantic.at<uint8_t>(int(y), int(x)))].add(estimate[i], gt);
            const double z = setup.calib.depthMetres(gt);
            const size_t band = size_t(std::upper_bound(edges.begin(), edges.end(), z) - edges.begin());
            work.bands[band].add(estimate[i], gt);
        }

    if (setup.options->pictures) {
        const std::string base = setup.pictureDir + "/frames/" + name;
        writePng(base + "_estimate.png", colourDisparity(estimate, w, h, setup.colourLo, setup.colourHi));
        writePng(base + "_truth.png", colourDisparity(truth.values, w, h, setup.colourLo, setup.colourHi));
        cv::Mat difference(int(h), int(w), CV_8UC1, cv::Scalar(0));
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const size_t i = size_t(y) * w + x;
                if (isValidDisparity(truth.values[i]) && isValidDisparity(estimate[i]))
                    difference.at<uint8_t>(int(y), int(x)) =
                        signedDifference8(double(estimate[i]) - double(truth.values[i]));
            }
        writePng(base + "_difference.png", difference);
    }
    return work;
}

// ---- report helpers ----

using Json = nlohmann::ordered_json;

void putMetrics(Json& j, const StereoMetrics& m) {
    j["gt_pixels"] = m.gtPixels;
    j["estimated_pixels"] = m.estimatedPixels;
    j["coverage"] = m.coverage;
    j["mean_abs_error"] = m.meanAbsError;
    j["mean_error"] = m.meanError;
    j["std_error"] = m.stdError;
    j["rms"] = m.rms;
    j["max_abs_error"] = m.maxAbsError;
    j["bad_0_5"] = m.bad[0];
    j["bad_1"] = m.bad[1];
    j["bad_2"] = m.bad[2];
    j["bad_4"] = m.bad[3];
    j["a50"] = m.accuracy[0];
    j["a90"] = m.accuracy[1];
    j["a95"] = m.accuracy[2];
    j["a99"] = m.accuracy[3];
    j["d1_all"] = m.d1;
    j["std_error_8bit"] = m.stdError8bit;
}

// (key, value) pairs in report order, for CSV and the difference object.
std::vector<std::pair<const char*, double>> metricFields(const StereoMetrics& m) {
    return {{"gt_pixels", double(m.gtPixels)},
            {"estimated_pixels", double(m.estimatedPixels)},
            {"coverage", m.coverage},
            {"mean_abs_error", m.meanAbsError},
            {"mean_error", m.meanError},
            {"std_error", m.stdError},
            {"rms", m.rms},
            {"max_abs_error", m.maxAbsError},
            {"bad_0_5", m.bad[0]},
            {"bad_1", m.bad[1]},
            {"bad_2", m.bad[2]},
            {"bad_4", m.bad[3]},
            {"a50", m.accuracy[0]},
            {"a90", m.accuracy[1]},
            {"a95", m.accuracy[2]},
            {"a99", m.accuracy[3]},
            {"d1_all", m.d1},
            {"std_error_8bit", m.stdError8bit}};
}

Json datasetJson(const DatasetEvaluation& d) {
    Json j;
    j["dataset"] = d.datasetDir;
    j["matcher"] = d.matcher;
    j["width"] = d.width;
    j["height"] = d.height;
    j["frames"] = d.frames.size();
    putMetrics(j, d.total.metrics());
    Json perFrame = Json::array();
    for (const FrameMetrics& f : d.frames) {
        Json fj;
        fj["frame"] = f.frame;
        fj["frames"] = 1;
        putMetrics(fj, f.metrics);
        perFrame.push_back(fj);
    }
    j["per_frame"] = perFrame;
    if (!d.classes.empty()) {
        Json classes = Json::object();
        for (const GroupMetrics& g : d.classes) putMetrics(classes[g.name], g.accumulator.metrics());
        j["classes"] = classes;
    }
    Json bands = Json::array();
    for (const GroupMetrics& g : d.bands) {
        Json bj;
        bj["band"] = g.name;
        bj["min_m"] = g.minMetres;
        bj["max_m"] = std::isinf(g.maxMetres) ? Json(nullptr) : Json(g.maxMetres);
        putMetrics(bj, g.accumulator.metrics());
        bands.push_back(bj);
    }
    j["distance_bands"] = bands;
    return j;
}

std::string csvNumber(double v) {
    if (!std::isfinite(v)) return "";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.9g", v);
    return buffer;
}

std::string fixed(double v, int decimals) {
    if (!std::isfinite(v)) return "n/a";
    char buffer[48];
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
    return buffer;
}
// Band edges as typed: "5", "12.5", "0.25".
std::string metres(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}
std::string percent(double v) {
    return std::isfinite(v) ? fixed(100.0 * v, 2) + " %" : "n/a";
}
std::string signedFixed(double v, int decimals) {
    return (v > 0 ? "+" : "") + fixed(v, decimals);
}

struct RowSpec {
    const char* label;
    double (*get)(const StereoMetrics&);
    bool fraction;
};

const RowSpec kRows[] = {
    {"pixels with ground truth", [](const StereoMetrics& m) { return double(m.gtPixels); }, false},
    {"coverage (estimated / ground truth)", [](const StereoMetrics& m) { return m.coverage; }, true},
    {"mean \\|e\\| (px)", [](const StereoMetrics& m) { return m.meanAbsError; }, false},
    {"mean e (px)", [](const StereoMetrics& m) { return m.meanError; }, false},
    {"std e (px)", [](const StereoMetrics& m) { return m.stdError; }, false},
    {"RMS (px)", [](const StereoMetrics& m) { return m.rms; }, false},
    {"std of 8-bit difference image", [](const StereoMetrics& m) { return m.stdError8bit; }, false},
    {"bad-0.5", [](const StereoMetrics& m) { return m.bad[0]; }, true},
    {"bad-1", [](const StereoMetrics& m) { return m.bad[1]; }, true},
    {"bad-2", [](const StereoMetrics& m) { return m.bad[2]; }, true},
    {"bad-4", [](const StereoMetrics& m) { return m.bad[3]; }, true},
    {"A50 (px)", [](const StereoMetrics& m) { return m.accuracy[0]; }, false},
    {"A90 (px)", [](const StereoMetrics& m) { return m.accuracy[1]; }, false},
    {"A95 (px)", [](const StereoMetrics& m) { return m.accuracy[2]; }, false},
    {"A99 (px)", [](const StereoMetrics& m) { return m.accuracy[3]; }, false},
    {"KITTI D1-all", [](const StereoMetrics& m) { return m.d1; }, true},
};

std::string cell(const RowSpec& row, const StereoMetrics& m) {
    double v = row.get(m);
    if (&row == &kRows[0]) return fixed(v, 0);
    return row.fraction ? percent(v) : fixed(v, 3);
}

std::string differenceCell(const RowSpec& row, const StereoMetrics& a, const StereoMetrics& b) {
    double d = row.get(a) - row.get(b);
    if (&row == &kRows[0]) return signedFixed(d, 0);
    if (!std::isfinite(d)) return "n/a";
    return row.fraction ? signedFixed(100.0 * d, 2) + " pt" : signedFixed(d, 3);
}

std::string groupTable(const std::vector<GroupMetrics>& groups) {
    std::string md = "| | pixels | coverage | mean \\|e\\| | mean e | std e | bad-2 | A90 | D1-all |\n"
                     "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const GroupMetrics& g : groups) {
        StereoMetrics m = g.accumulator.metrics();
        if (m.gtPixels == 0) continue;
        md += "| " + g.name + " | " + std::to_string(m.gtPixels) + " | " + percent(m.coverage) + " | " +
              fixed(m.meanAbsError, 3) + " | " + fixed(m.meanError, 3) + " | " + fixed(m.stdError, 3) + " | " +
              percent(m.bad[2]) + " | " + fixed(m.accuracy[1], 3) + " | " + percent(m.d1) + " |\n";
    }
    return md;
}

// Line plot of signed-error histograms (fraction of estimated pixels per pixel of error), one curve per input.
struct Curve {
    std::string label;
    cv::Scalar colour; // BGR
    const ErrorAccumulator* accumulator;
};

void plotHistograms(const std::string& path, const std::string& title, const std::vector<Curve>& curves) {
    const int W = 720, H = 400, left = 70, right = 20, top = 40, bottom = 50;
    cv::Mat canvas(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    // Range: the smallest power of two (4..256 px) that holds the A95 of every curve.
    double range = 4;
    for (const Curve& c : curves) {
        StereoMetrics m = c.accumulator->metrics();
        while (std::isfinite(m.accuracy[2]) && range < m.accuracy[2] && range < ErrorAccumulator::kSignedRange)
            range *= 2;
    }
    const int plotBins = 64;
    const double binWidth = 2 * range / plotBins; // a multiple of the 1/8 px accumulator bins
    std::vector<std::vector<double>> densities;
    std::vector<double> outside;
    double yMax = 1e-9;
    for (const Curve& c : curves) {
        std::vector<double> density(plotBins, 0.0);
        const std::vector<uint64_t>& hist = c.accumulator->signedHistogram();
        const double n = double(c.accumulator->estimatedPixels());
        uint64_t out = 0;
        for (size_t i = 0; i < hist.size(); ++i) {
            const double low = ErrorAccumulator::signedBinLow(i);
            if (low < -range || low >= range) {
                out += hist[i];
                continue;
            }
            density[size_t((low + range) / binWidth)] += double(hist[i]);
        }
        for (double& v : density) {
            v = n > 0 ? v / n / binWidth : 0.0;
            yMax = std::max(yMax, v);
        }
        densities.push_back(density);
        outside.push_back(n > 0 ? double(out) / n : 0.0);
    }
    yMax *= 1.08;
    auto px = [&](double e) { return left + int(std::lround((e + range) / (2 * range) * (W - left - right))); };
    auto py = [&](double v) { return H - bottom - int(std::lround(v / yMax * (H - top - bottom))); };
    const cv::Scalar black(0, 0, 0), grey(200, 200, 200);
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    for (int k = -4; k <= 4; ++k) {
        const double e = range * k / 4;
        cv::line(canvas, {px(e), top}, {px(e), H - bottom}, k == 0 ? cv::Scalar(150, 150, 150) : grey, 1);
        std::string label = fixed(e, range >= 16 ? 0 : 1);
        cv::putText(canvas, label, {px(e) - 12, H - bottom + 18}, font, 0.4, black, 1, cv::LINE_AA);
    }
    for (int k = 0; k <= 4; ++k) {
        const double v = yMax / 1.08 * k / 4;
        cv::line(canvas, {left, py(v)}, {W - right, py(v)}, grey, 1);
        cv::putText(canvas, fixed(v, 3), {4, py(v) + 4}, font, 0.4, black, 1, cv::LINE_AA);
    }
    cv::rectangle(canvas, {left, top}, {W - right, H - bottom}, black, 1);
    cv::putText(canvas, title + "  (y: fraction of estimated pixels per px of error)", {left, 24}, font, 0.45, black, 1,
                cv::LINE_AA);
    cv::putText(canvas, "signed error e = estimate - truth (px)", {left + 180, H - 12}, font, 0.45, black, 1,
                cv::LINE_AA);
    for (size_t c = 0; c < curves.size(); ++c) {
        std::vector<cv::Point> points;
        for (int b = 0; b < plotBins; ++b) {
            const double e0 = -range + b * binWidth;
            points.push_back({px(e0), py(densities[c][b])});
            points.push_back({px(e0 + binWidth), py(densities[c][b])});
        }
        cv::polylines(canvas, points, false, curves[c].colour, 2, cv::LINE_AA);
        const int ly = top + 16 + int(c) * 18;
        cv::line(canvas, {W - right - 250, ly - 4}, {W - right - 225, ly - 4}, curves[c].colour, 2);
        cv::putText(canvas, curves[c].label + " (" + fixed(100 * outside[c], 1) + " % outside)", {W - right - 220, ly},
                    font, 0.4, black, 1, cv::LINE_AA);
    }
    writePng(path, canvas);
}

std::string markdownPictures(const std::string& prefix, uint32_t frame) {
    const std::string base = prefix + "frames/" + frameName(frame);
    return "| estimate | ground truth | signed difference (127 = 0 px) |\n|---|---|---|\n| ![](" + base +
           "_estimate.png) | ![](" + base + "_truth.png) | ![](" + base + "_difference.png) |\n";
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
    int mode = cv::StereoSGBM::MODE_SGBM;
    switch (r.options.mode) {
    case SgbmMode::Sgbm:
        mode = cv::StereoSGBM::MODE_SGBM;
        break;
    case SgbmMode::HH:
        mode = cv::StereoSGBM::MODE_HH;
        break;
    case SgbmMode::ThreeWay:
        mode = cv::StereoSGBM::MODE_SGBM_3WAY;
        break;
    case SgbmMode::HH4:
        mode = cv::StereoSGBM::MODE_HH4;
        break;
    }
    cv::Ptr<cv::StereoSGBM> sgbm =
        cv::StereoSGBM::create(0, r.numDisparities, r.options.blockSize, r.p1, r.p2, r.options.disp12MaxDiff, 0,
                               r.options.uniquenessRatio, r.options.speckleWindowSize, r.options.speckleRange, mode);
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

std::vector<uint32_t> listDatasetFrames(const std::string& dir) {
    const std::string folder = dir + "/disparity";
    std::error_code ec;
    require(fs::is_directory(folder, ec), dir + " has no ground-truth folder '" + folder + "'");
    std::vector<uint32_t> frames;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string stem = entry.path().stem().string(), ext = entry.path().extension().string();
        if (stem.size() != 6 || !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
            continue;
        if (ext == ".pfm" || ext == ".exr" || ext == ".png") frames.push_back(uint32_t(std::stoul(stem)));
    }
    require(!ec, "cannot list '" + folder + "': " + ec.message());
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

DisparityMap readGroundTruth(const std::string& dir, uint32_t frame) {
    const std::string base = dir + "/disparity/" + frameName(frame);
    if (isFile(base + ".pfm")) return readPfm(base + ".pfm");
    if (isFile(base + ".exr")) {
        ImageData image = loadImage(base + ".exr");
        require(image.channels == 1, base + ".exr: expected a one-channel (Y) disparity image");
        DisparityMap map{image.width, image.height, std::move(image.samples)};
        for (float& v : map.values)
            if (!isValidDisparity(v)) v = 0.0f;
        return map;
    }
    if (isFile(base + ".png")) return readKittiPng(base + ".png");
    throw Error("missing ground truth for frame " + frameName(frame) + ": no " + base + ".pfm, .exr or .png");
}

DatasetEvaluation evaluateDataset(const std::string& datasetDir, const std::string& disparitiesDir,
                                  const EvaluationOptions& options, const std::string& pictureDir) {
    std::error_code ec;
    require(fs::is_directory(datasetDir, ec), "dataset folder '" + datasetDir + "' does not exist");
    if (!disparitiesDir.empty())
        require(fs::is_directory(disparitiesDir, ec), "disparities folder '" + disparitiesDir + "' does not exist");
    const std::vector<double>& edges = options.bandEdgesMetres;
    for (size_t i = 0; i < edges.size(); ++i)
        require(edges[i] > 0 && std::isfinite(edges[i]) && (i == 0 || edges[i] > edges[i - 1]),
                "distance band edges must be positive and increasing");

    DatasetSetup setup;
    setup.dir = datasetDir;
    setup.disparitiesDir = disparitiesDir;
    setup.pictureDir = pictureDir;
    setup.options = &options;
    setup.calib = readMiddleburyCalib(datasetDir + "/calib.txt");
    setup.semantic = fs::is_directory(datasetDir + "/semantic", ec);

    std::vector<uint32_t> frames = listDatasetFrames(datasetDir);
    if (options.frames)
        std::erase_if(frames, [&](uint32_t f) { return f < options.frames->first || f >= options.frames->second; });
    require(!frames.empty(), datasetDir + ": no frames to evaluate in '" + datasetDir + "/disparity'");

    DatasetEvaluation result;
    result.datasetDir = datasetDir;
    result.calib = setup.calib;
    result.width = setup.calib.width;
    result.height = setup.calib.height;
    if (disparitiesDir.empty()) {
        setup.sgbm = resolveSgbm(options.sgbm, setup.calib, setup.calib.width);
        const ResolvedSgbm& s = *setup.sgbm;
        result.sgbm = s;
        result.matcher =
            std::string("OpenCV StereoSGBM: mode ") + sgbmModeName(s.options.mode) + ", " +
            (s.options.gray ? "grey" : "colour") + " (cn " + std::to_string(s.channels) + "), block size " +
            std::to_string(s.options.blockSize) + ", P1 " + std::to_string(s.p1) + ", P2 " + std::to_string(s.p2) +
            ", minDisparity 0, numDisparities " + std::to_string(s.numDisparities) + ", uniqueness " +
            std::to_string(s.options.uniquenessRatio) + " %, speckle window " +
            std::to_string(s.options.speckleWindowSize) + " range " + std::to_string(s.options.speckleRange) +
            ", disp12MaxDiff " + std::to_string(s.options.disp12MaxDiff);
    } else {
        result.matcher = "disparities read from " + disparitiesDir;
    }
    // Colour scale shared by estimate and truth: calib.txt's vmin..vmax when given, else 0..numDisparities.
    setup.colourLo = 0;
    setup.colourHi = setup.sgbm ? setup.sgbm->numDisparities : double(setup.calib.ndisp);
    if (setup.calib.vmax > setup.calib.vmin) {
        setup.colourLo = setup.calib.vmin;
        setup.colourHi = setup.calib.vmax;
    }
    if (options.pictures) makeDirectory(pictureDir + "/frames");
    if (options.saveDisparities && setup.sgbm) makeDirectory(pictureDir + "/disparity");

    if (setup.semantic)
        for (const char* name : kClassNames) result.classes.push_back({name, 0, 0, {}});
    for (size_t i = 0; i <= edges.size(); ++i) {
        GroupMetrics band;
        band.minMetres = i == 0 ? 0.0 : edges[i - 1];
        band.maxMetres = i == edges.size() ? INFINITY : edges[i];
        band.name = metres(band.minMetres) + (i == edges.size() ? "+ m" : "-" + metres(band.maxMetres) + " m");
        result.bands.push_back(std::move(band));
    }

    SingleThreadedOpenCV singleThreaded;
    unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min<unsigned>(threads, unsigned(frames.size()));
    // Frames are matched in batches of `threads` and merged in frame order: double sums are then added in the
    // same order whatever the thread count, and at most `threads` frames' histograms are alive at once.
    for (size_t begin = 0; begin < frames.size(); begin += threads) {
        const size_t count = std::min<size_t>(threads, frames.size() - begin);
        std::vector<FrameWork> batch(count);
        std::vector<std::exception_ptr> errors(count);
        auto work = [&](size_t k) {
            try {
                batch[k] = evaluateFrame(setup, frames[begin + k]);
            } catch (...) {
                errors[k] = std::current_exception();
            }
        };
        std::vector<std::thread> pool;
        for (size_t k = 1; k < count; ++k) pool.emplace_back(work, k);
        work(0);
        for (std::thread& t : pool) t.join();
        for (const std::exception_ptr& e : errors)
            if (e) std::rethrow_exception(e);
        for (FrameWork& f : batch) {
            result.frames.push_back({f.frame, f.total.metrics()});
            result.total.merge(f.total);
            for (size_t c = 0; c < f.classes.size(); ++c) result.classes[c].accumulator.merge(f.classes[c]);
            for (size_t b = 0; b < f.bands.size(); ++b) result.bands[b].accumulator.merge(f.bands[b]);
            result.matchSeconds += f.matchSeconds;
        }
    }
    return result;
}

std::string metricsJson(const EvaluationReport& report) {
    Json j = datasetJson(report.main);
    if (report.against) {
        j["against"] = datasetJson(*report.against);
        Json difference;
        const auto a = metricFields(report.main.total.metrics()), b = metricFields(report.against->total.metrics());
        difference["frames"] = int64_t(report.main.frames.size()) - int64_t(report.against->frames.size());
        for (size_t i = 0; i < a.size(); ++i) {
            const std::string key = a[i].first;
            if (key == "gt_pixels" || key == "estimated_pixels") // counts stay integers
                difference[key] = int64_t(a[i].second) - int64_t(b[i].second);
            else
                difference[key] = a[i].second - b[i].second;
        }
        j["difference"] = difference;
    }
    return j.dump(2) + "\n";
}

std::string metricsCsv(const EvaluationReport& report) {
    std::string csv = "dataset,frame";
    for (const auto& field : metricFields(StereoMetrics{})) csv += std::string(",") + field.first;
    csv += "\n";
    auto rows = [&](const DatasetEvaluation& d, const char* label) {
        auto line = [&](const std::string& frame, const StereoMetrics& m) {
            csv += std::string(label) + "," + frame;
            for (const auto& field : metricFields(m)) csv += "," + csvNumber(field.second);
            csv += "\n";
        };
        for (const FrameMetrics& f : d.frames) line(frameName(f.frame), f.metrics);
        line("all", d.total.metrics());
    };
    rows(report.main, "main");
    if (report.against) rows(*report.against, "against");
    return csv;
}

std::string reportMarkdown(const EvaluationReport& report) {
    const DatasetEvaluation& m = report.main;
    const StereoMetrics mt = m.total.metrics();
    std::string md = "# Stereo evaluation of " + m.datasetDir + "\n\n";
    md += "- Matcher: " + m.matcher + "\n";
    md += "- " + std::to_string(m.frames.size()) + " frames of " + std::to_string(m.width) + "x" +
          std::to_string(m.height) +
          " px; errors e = estimate - ground truth over pixels with both (see "
          "docs/evaluation.md); metrics pooled over all pixels of all frames.\n";
    if (report.against) {
        const DatasetEvaluation& a = *report.against;
        md += "- Against: " + a.datasetDir + " (" + std::to_string(a.frames.size()) + " frames; " + a.matcher + ")\n";
    }
    md += "\n## Overall\n\n";
    const StereoMetrics at = report.against ? report.against->total.metrics() : StereoMetrics{};
    md += report.against ? "| metric | " + m.datasetDir + " | " + report.against->datasetDir +
                               " | difference |\n|---|---:|---:|---:|\n"
                         : "| metric | value |\n|---|---:|\n";
    for (const RowSpec& row : kRows) {
        md += std::string("| ") + row.label + " | " + cell(row, mt);
        if (report.against) md += " | " + cell(row, at) + " | " + differenceCell(row, mt, at);
        md += " |\n";
    }
    auto groups = [&](const DatasetEvaluation& d, const std::string& suffix) {
        if (!d.classes.empty()) md += "\n## By semantic class" + suffix + "\n\n" + groupTable(d.classes);
        md += "\n## By distance (ground-truth depth)" + suffix + "\n\n" + groupTable(d.bands);
    };
    groups(m, "");
    if (report.against) groups(*report.against, " — " + report.against->datasetDir);

    md += "\n## Error histograms\n\n![signed error histogram](error_histogram.png)\n";
    if (!m.classes.empty()) md += "\n![signed error histogram by class](error_histogram_classes.png)\n";

    auto perFrame = [&](const DatasetEvaluation& d, const std::string& suffix) {
        md += "\n## Per frame" + suffix +
              "\n\n| frame | coverage | mean \\|e\\| | mean e | std e | RMS | bad-1 | bad-2 | D1-all |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const FrameMetrics& f : d.frames) {
            const StereoMetrics& s = f.metrics;
            md += "| " + frameName(f.frame) + " | " + percent(s.coverage) + " | " + fixed(s.meanAbsError, 3) + " | " +
                  fixed(s.meanError, 3) + " | " + fixed(s.stdError, 3) + " | " + fixed(s.rms, 3) + " | " +
                  percent(s.bad[1]) + " | " + percent(s.bad[2]) + " | " + percent(s.d1) + " |\n";
        }
    };
    perFrame(m, "");
    if (report.against) perFrame(*report.against, " — " + report.against->datasetDir);

    if (!m.frames.empty() && fs::exists(report.outDir + "/frames/" + frameName(m.frames[0].frame) + "_estimate.png")) {
        md += "\n## Frame " + frameName(m.frames[0].frame) +
              "\n\nDisparity colour scale: turbo, shared by estimate and ground truth; black = no value. "
              "All frames' pictures are in frames/.\n\n" +
              markdownPictures("", m.frames[0].frame);
        if (report.against && !report.against->frames.empty())
            md += "\n" + report.against->datasetDir + ":\n\n" +
                  markdownPictures("against/", report.against->frames[0].frame);
    }
    return md;
}

EvaluationReport runEvaluation(const EvaluationOptions& options) {
    std::error_code ec;
    require(!options.datasetDir.empty(), "no dataset folder given");
    require(fs::is_directory(options.datasetDir, ec), "dataset folder '" + options.datasetDir + "' does not exist");
    if (!options.againstDir.empty())
        require(fs::is_directory(options.againstDir, ec),
                "--against dataset folder '" + options.againstDir + "' does not exist");
    require(options.againstDisparitiesDir.empty() || !options.againstDir.empty(),
            "--against-disparities needs --against DATASET");
    require(options.againstDir.empty() || options.disparitiesDir.empty() == options.againstDisparitiesDir.empty(),
            "with --against, give estimates for both datasets (--disparities and --against-disparities) or for "
            "neither (both matched by SGBM)");
    EvaluationReport report;
    report.outDir = options.outDir.empty() ? options.datasetDir + "/eval" : options.outDir;
    makeDirectory(report.outDir);
    auto log = [&](const std::string& line) {
        if (options.log) options.log(line);
    };
    auto summary = [&](const DatasetEvaluation& d) {
        StereoMetrics t = d.total.metrics();
        std::string line = d.datasetDir + ": " + std::to_string(d.frames.size()) + " frames, mean |e| " +
                           fixed(t.meanAbsError, 3) + " px, mean e " + fixed(t.meanError, 3) + " px, bad-2 " +
                           percent(t.bad[2]) + ", D1 " + percent(t.d1) + ", coverage " + percent(t.coverage);
        if (d.sgbm) line += "; SGBM " + fixed(d.matchSeconds / double(d.frames.size()), 3) + " s per frame";
        log(line);
    };
    report.main = evaluateDataset(options.datasetDir, options.disparitiesDir, options, report.outDir);
    summary(report.main);
    if (!options.againstDir.empty()) {
        const std::string againstOut = report.outDir + "/against";
        if (options.pictures || options.saveDisparities) makeDirectory(againstOut);
        report.against = evaluateDataset(options.againstDir, options.againstDisparitiesDir, options, againstOut);
        summary(*report.against);
    }

    // Legend labels: the datasets' folder names, unless they are the same.
    auto folderName = [](const std::string& dir) {
        fs::path p = fs::path(dir).lexically_normal();
        return (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
    };
    std::string mainLabel = folderName(report.main.datasetDir);
    std::string againstLabel = report.against ? folderName(report.against->datasetDir) : "against";
    if (mainLabel.empty() || mainLabel == againstLabel) mainLabel = "main", againstLabel = "against";
    std::vector<Curve> curves = {{mainLabel, cv::Scalar(200, 90, 20), &report.main.total}};
    if (report.against) curves.push_back({againstLabel, cv::Scalar(30, 30, 220), &report.against->total});
    plotHistograms(report.outDir + "/error_histogram.png", "Signed disparity error, all pixels", curves);
    if (!report.main.classes.empty()) {
        const cv::Scalar colours[] = {{40, 160, 40}, {40, 110, 170}, {180, 60, 180}, {120, 120, 120}};
        std::vector<Curve> classCurves;
        for (size_t c = 0; c < report.main.classes.size(); ++c)
            if (report.main.classes[c].accumulator.estimatedPixels() > 0)
                classCurves.push_back({report.main.classes[c].name, colours[c], &report.main.classes[c].accumulator});
        plotHistograms(report.outDir + "/error_histogram_classes.png", "Signed disparity error by semantic class",
                       classCurves);
    }
    writeTextAtomically(report.outDir + "/metrics.json", metricsJson(report));
    writeTextAtomically(report.outDir + "/metrics.csv", metricsCsv(report));
    writeTextAtomically(report.outDir + "/report.md", reportMarkdown(report));
    log("report written to " + report.outDir + "/report.md");
    return report;
}

} // namespace sward
