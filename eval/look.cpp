#include "eval/look.h"

#include "common/error.h"
#include "common/staged_folder.h"
#include "common/stopwatch.h"
#include "dataset/naming.h"
#include "eval/dataset_reader.h"
#include "eval/frame_batches.h"
#include "eval/look_regions.h"
#include "eval/look_report.h"
#include "eval/number_format.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

namespace fs = std::filesystem;

namespace sward {

namespace {

std::vector<uint32_t> chooseFrames(const LookOptions& options) {
    std::vector<uint32_t> frames = listFrameFiles(options.datasetDir, kPreviewFolder, {".png"}, "preview folder");
    if (options.frames)
        std::erase_if(frames, [&](uint32_t f) { return f < options.frames->first || f >= options.frames->second; });
    require(!frames.empty(), options.datasetDir + ": no frame to measure in '" + options.datasetDir + "/" +
                                 kPreviewFolder + "'" + (options.frames ? " within --frames" : ""));
    return frames;
}

LookImageResult measureImage(const std::string& name, const cv::Mat& bgr, const std::vector<LookRegion>& regions) {
    const LookImage image = prepareLookImage(bgr);
    LookImageResult result{name, uint32_t(bgr.cols), uint32_t(bgr.rows), {}};
    for (const LookRegion& region : regions)
        result.regions.emplace_back(region.name, measureRegion(image, region.mask));
    return result;
}

LookImageResult measureFrame(const std::string& dir, uint32_t frame) {
    const cv::Mat bgr = readPreview(dir, kPreviewFolder, frame, false);
    const cv::Mat semantic = readSemantic(dir, frame, uint32_t(bgr.cols), uint32_t(bgr.rows));
    LookImageResult result = measureImage(frameName(frame), bgr, swardRegions(semantic));
    const LookStatistics& all = result.regions[0].second;
    const LookStatistics& turf = result.regions[3].second;
    if (all.pixels > 0) {
        const double smooth = turf.pixels == 0 ? 0 : std::round(double(turf.pixels) * (1 - turf.sharpFraction));
        result.smoothTurfShare = smooth / double(all.pixels);
    }
    return result;
}

std::vector<uint32_t> indices(size_t n) {
    std::vector<uint32_t> all(n);
    std::iota(all.begin(), all.end(), 0u);
    return all;
}

std::vector<std::string> regionOrder(const LookResult& result) {
    std::vector<std::string> order(std::begin(kSwardRegionNames), std::end(kSwardRegionNames));
    for (const LookImageResult& image : result.reference)
        for (const auto& [name, _] : image.regions)
            if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
    return order;
}

double stdOf(const std::vector<double>& values) {
    if (values.empty()) return NAN;
    double sum = 0, squares = 0;
    for (double v : values) sum += v;
    const double mean = sum / double(values.size());
    for (double v : values) squares += (v - mean) * (v - mean);
    return std::sqrt(squares / double(values.size()));
}

} // namespace

std::vector<LookField> lookFields(const LookStatistics& s) {
    std::vector<LookField> fields = {
        {"pixels", double(s.pixels), false},
        {"grey_mean", s.greyMean, true},
        {"grey_std", s.greyStd, true},
        {"saturation_mean", s.saturationMean, true},
        {"value_std", s.valueStd, true},
        {"hue_std_deg", s.hueStdDegrees, true},
        {"gradient_mean", s.gradientMean, true},
        {"gradient_p99", s.gradientP99, true},
        {"dx_excess_kurtosis", s.dxKurtosis, true},
    };
    static const char* laplacian[] = {"laplacian_rms_0", "laplacian_rms_1", "laplacian_rms_2", "laplacian_rms_3",
                                      "laplacian_rms_4"};
    for (int k = 0; k < kLookPyramidLevels; ++k) fields.push_back({laplacian[k], s.laplacianRms[size_t(k)], true});
    fields.insert(fields.end(), {
                                    {"spectrum_slope", s.spectrumSlope, true},
                                    {"spectrum_slope_high", s.spectrumSlopeHigh, true},
                                    {"spectrum_windows", double(s.spectrumWindows), false},
                                    {"orb_per_mp", s.keypointsPerMegapixel[0], true},
                                    {"sift_per_mp", s.keypointsPerMegapixel[1], true},
                                    {"fast_per_mp", s.keypointsPerMegapixel[2], true},
                                    {"eroded_pixels", double(s.erodedPixels), false},
                                    {"sharp_fraction", s.sharpFraction, true},
                                    {"noise_floor", s.noiseFloor, true},
                                    {"noise_blocks", double(s.noiseBlocks), false},
                                });
    return fields;
}

LookSummaries summarise(const std::vector<LookImageResult>& images) {
    std::map<std::string, std::vector<std::vector<double>>> values; // region -> field -> values
    LookSummaries summaries;
    for (const LookImageResult& image : images)
        for (const auto& [name, stats] : image.regions) {
            if (stats.pixels == 0) continue;
            const std::vector<LookField> fields = lookFields(stats);
            LookSummary& summary = summaries[name];
            std::vector<std::vector<double>>& columns = values[name];
            if (summary.keys.empty())
                for (const LookField& f : fields) summary.keys.push_back(f.key);
            columns.resize(fields.size());
            for (size_t i = 0; i < fields.size(); ++i)
                if (std::isfinite(fields[i].value)) columns[i].push_back(fields[i].value);
            ++summary.images;
        }
    for (auto& [name, summary] : summaries)
        for (const std::vector<double>& column : values[name]) {
            summary.median.push_back(percentileOf(column, 0.5));
            summary.q1.push_back(percentileOf(column, 0.25));
            summary.q3.push_back(percentileOf(column, 0.75));
            summary.std.push_back(stdOf(column));
        }
    return summaries;
}

double lookGap(const LookSummary& sward, const LookSummary& real, size_t field) {
    if (field >= sward.median.size() || field >= real.median.size()) return NAN;
    const double iqr = real.q3[field] - real.q1[field];
    const double spread = iqr > 0 ? iqr : real.std[field];
    if (!(spread > 0) || !std::isfinite(sward.median[field]) || !std::isfinite(real.median[field])) return NAN;
    return (sward.median[field] - real.median[field]) / spread;
}

LookResult evaluateLook(const LookOptions& options) {
    require(!options.datasetDir.empty(), "no dataset folder given");
    std::error_code ec;
    require(fs::is_directory(options.datasetDir, ec), "dataset folder '" + options.datasetDir + "' does not exist");
    LookResult result;
    result.datasetDir = options.datasetDir;
    result.referenceDir = options.referenceDir;
    const std::vector<uint32_t> frames = chooseFrames(options);
    // The reference folder is read before the frames are measured, so a bad one fails at once.
    const std::vector<ReferenceImage> reference =
        options.referenceDir.empty() ? std::vector<ReferenceImage>() : readReferenceImages(options.referenceDir);
    evaluateInFrameOrder<LookImageResult>(
        frames, options.threads, [&](uint32_t frame) { return measureFrame(options.datasetDir, frame); },
        [&](LookImageResult& image) {
            if (options.log) options.log("frame " + image.name + " measured");
            result.frames.push_back(std::move(image));
        });
    evaluateInFrameOrder<LookImageResult>(
        indices(reference.size()), options.threads,
        [&](uint32_t i) { return measureImage(reference[i].file, reference[i].bgr, reference[i].regions); },
        [&](LookImageResult& image) { result.reference.push_back(std::move(image)); });
    result.regionOrder = regionOrder(result);
    result.sward = summarise(result.frames);
    std::vector<double> shares;
    for (const LookImageResult& frame : result.frames)
        if (std::isfinite(frame.smoothTurfShare)) shares.push_back(frame.smoothTurfShare);
    result.smoothTurfShare = percentileOf(shares, 0.5);
    result.real = summarise(result.reference);
    return result;
}

LookResult runLook(const LookOptions& options) {
    const std::string outDir = options.outDir.empty() ? options.datasetDir + "/eval-look" : options.outDir;
    const Stopwatch clock;
    LookResult result = evaluateLook(options);
    // The report appears whole or not at all, in a folder locked for one writer; DATASET/eval-look as a link is
    // refused.
    StagedFolder staged(outDir, "report folder", !options.outDir.empty());
    writeLookReport(result, staged.path(), options.pictures);
    staged.commit();
    if (options.log) {
        options.log(result.datasetDir + ": " + std::to_string(result.frames.size()) + " frames" +
                    (result.reference.empty() ? "" : ", " + std::to_string(result.reference.size()) + " real images") +
                    "; " + fixed(clock.seconds(), 2) + " s");
        options.log("report written to " + outDir + "/report.md");
    }
    return result;
}

} // namespace sward
