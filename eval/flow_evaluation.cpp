#include "eval/flow_evaluation.h"

#include "common/error.h"
#include "common/staged_folder.h"
#include "common/stopwatch.h"
#include "dataset/naming.h"
#include "eval/dataset_reader.h"
#include "eval/flow_report.h"
#include "eval/frame_batches.h"
#include "eval/number_format.h"
#include "eval/pictures.h"
#include "eval/splits.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace sward {

namespace {

// End-point errors from 0 (dark blue) to this many pixels (dark red) in the EPE pictures; larger ones saturate.
constexpr double kEpePictureMax = 8.0;

// What every frame of the dataset is evaluated with.
struct FlowSetup {
    const FlowEvaluationOptions* options = nullptr;
    std::string pictureDir;
    uint32_t width = 0, height = 0;
    bool semantic = false, masks = false, depth = false;
};

// One frame's accumulators, merged into the dataset's in frame order.
struct FlowFrameWork {
    uint32_t frame = 0;
    FlowErrors total;
    std::vector<FlowErrors> classes, bands;
    double seconds = 0;
};

bool isDirectory(const std::string& path) {
    std::error_code ec;
    return fs::is_directory(path, ec);
}

bool isFile(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

void requireOptions(const FlowEvaluationOptions& options) {
    require(!options.datasetDir.empty(), "no dataset folder given");
    require(isDirectory(options.datasetDir), "dataset folder '" + options.datasetDir + "' does not exist");
    require((options.method == FlowMethod::Files) == !options.flowDir.empty(),
            options.flowDir.empty() ? "method 'files' needs a folder of flow files (--flow DIR)"
                                    : std::string("--flow reads flow files: it cannot be combined with method '") +
                                          flowMethodName(options.method) + "'");
    if (!options.flowDir.empty())
        require(isDirectory(options.flowDir), "flow folder '" + options.flowDir + "' does not exist");
    requireBandEdges(options.bandEdgesMetres);
}

// The frames with ground-truth forward flow, restricted to options.frames. The sequence's last frame has a forward
// flow too, but its target image was never rendered: it is left out when preview/ lacks frame + 1.
std::vector<uint32_t> framesToEvaluate(const FlowEvaluationOptions& options) {
    const std::string& dir = options.datasetDir;
    const std::string truthDir = dir + "/" + kFlowForwardFolder;
    require(isDirectory(truthDir), dir + " has no optical-flow ground truth: no folder '" + truthDir +
                                       "' (render the scene with \"render\": {\"flow\": true})");
    std::vector<uint32_t> frames = listFrameFiles(dir, kFlowForwardFolder, {".flo", ".png"}, "flow folder");
    if (!frames.empty() && !isFile(dir + "/" + frameFile(kPreviewFolder, frames.back() + 1, ".png"))) frames.pop_back();
    if (options.frames)
        std::erase_if(frames, [&](uint32_t f) { return f < options.frames->first || f >= options.frames->second; });
    require(!frames.empty(), dir + ": no frames to evaluate in '" + dir + "/" + kFlowForwardFolder +
                                 "' (a frame needs its flow and the next frame's preview)");
    return frames;
}

// The frame's flow by the chosen method (timed into work.seconds), or the estimate read from the flow folder.
FlowField estimateFlow(const FlowSetup& setup, FlowFrameWork& work) {
    const FlowEvaluationOptions& options = *setup.options;
    if (options.method == FlowMethod::Files)
        return readFlowEstimate(options.flowDir, work.frame, setup.width, setup.height);
    const cv::Mat first = readPreview(options.datasetDir, kPreviewFolder, work.frame, true);
    const cv::Mat second = readPreview(options.datasetDir, kPreviewFolder, work.frame + 1, true);
    for (const auto& [image, frame] : {std::pair{&first, work.frame}, std::pair{&second, work.frame + 1}})
        require(uint32_t(image->cols) == setup.width && uint32_t(image->rows) == setup.height,
                options.datasetDir + "/" + frameFile(kPreviewFolder, frame, ".png") + " is " +
                    std::to_string(image->cols) + "x" + std::to_string(image->rows) + ", the flow ground truth " +
                    std::to_string(setup.width) + "x" + std::to_string(setup.height));
    const Stopwatch computing;
    FlowField flow = computeFlow(options.method, first, second);
    work.seconds = computing.seconds();
    return flow;
}

// Adds every pixel with truth to the total, its class group and the distance band of its depth in this frame.
void accumulateErrors(const FlowSetup& setup, const FlowField& truth, const FlowField& estimate, FlowFrameWork& work) {
    const std::string& dir = setup.options->datasetDir;
    const uint32_t w = setup.width, h = setup.height;
    const cv::Mat mask = setup.masks ? readFlowMask(dir, work.frame, w, h) : cv::Mat();
    const cv::Mat semantic = setup.semantic ? readSemantic(dir, work.frame, w, h) : cv::Mat();
    const std::vector<float> depth = setup.depth ? readDepth(dir, work.frame, w, h) : std::vector<float>();
    const std::vector<double>& edges = setup.options->bandEdgesMetres;
    if (setup.semantic) work.classes.resize(kClassGroups.size());
    if (setup.depth) work.bands.resize(edges.size() + 1);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (!isValidFlow(truth.u(i), truth.v(i))) continue;
            const bool visible = setup.masks && mask.at<uint8_t>(int(y), int(x)) == 255;
            const float eu = estimate.u(i), ev = estimate.v(i), tu = truth.u(i), tv = truth.v(i);
            work.total.add(eu, ev, tu, tv, visible);
            if (setup.semantic)
                work.classes[classGroupOf(semantic.at<uint8_t>(int(y), int(x)))].add(eu, ev, tu, tv, visible);
            if (setup.depth) work.bands[bandIndex(edges, depth[i])].add(eu, ev, tu, tv, visible);
        }
}

// Truth and estimate on one colour scale (the truth's largest motion), and the end-point error map.
void writeFramePictures(const FlowSetup& setup, const FlowField& truth, const FlowField& estimate, uint32_t frame) {
    double maxMagnitude = 1.0;
    std::vector<float> epe(truth.uv.size() / 2, std::numeric_limits<float>::quiet_NaN());
    for (size_t i = 0; i < epe.size(); ++i) {
        if (!isValidFlow(truth.u(i), truth.v(i))) continue;
        maxMagnitude = std::max(maxMagnitude, std::hypot(double(truth.u(i)), double(truth.v(i))));
        if (isValidFlow(estimate.u(i), estimate.v(i)))
            epe[i] = float(std::hypot(double(estimate.u(i)) - truth.u(i), double(estimate.v(i)) - truth.v(i)));
    }
    const std::string base = setup.pictureDir + "/frames/" + frameName(frame);
    writePng(base + "_truth.png", colourFlow(truth, maxMagnitude));
    writePng(base + "_estimate.png", colourFlow(estimate, maxMagnitude));
    writePng(base + "_epe.png", colourValues(epe, setup.width, setup.height, 0.0, kEpePictureMax,
                                             [](float v) { return std::isfinite(v); }));
}

FlowFrameWork evaluateFrame(const FlowSetup& setup, uint32_t frame) {
    FlowFrameWork work;
    work.frame = frame;
    const FlowField truth = readFlowTruth(setup.options->datasetDir, frame);
    require(truth.width == setup.width && truth.height == setup.height,
            "the flow ground truth of frame " + frameName(frame) + " is " + std::to_string(truth.width) + "x" +
                std::to_string(truth.height) + ", that of the first frame " + std::to_string(setup.width) + "x" +
                std::to_string(setup.height));
    const FlowField estimate = estimateFlow(setup, work);
    accumulateErrors(setup, truth, estimate, work);
    if (setup.options->pictures) writeFramePictures(setup, truth, estimate, frame);
    return work;
}

void merge(const FlowFrameWork& work, FlowEvaluation& result) {
    result.frames.push_back({work.frame, work.total.all.metrics(), work.total.noc.metrics()});
    result.total.merge(work.total);
    for (size_t c = 0; c < work.classes.size(); ++c) result.classes[c].errors.merge(work.classes[c]);
    for (size_t b = 0; b < work.bands.size(); ++b) result.bands[b].errors.merge(work.bands[b]);
    result.flowSeconds += work.seconds;
}

// The dataset's optional inputs, its size (the first frame's truth) and the empty groups of the report.
FlowSetup prepare(const FlowEvaluationOptions& options, uint32_t firstFrame, FlowEvaluation& result) {
    const std::string& dir = options.datasetDir;
    FlowSetup setup;
    setup.options = &options;
    setup.semantic = isDirectory(dir + "/" + kSemanticFolder);
    setup.masks = isDirectory(dir + "/" + kFlowForwardMaskFolder);
    setup.depth = isDirectory(dir + "/" + kDepthFolder);
    const FlowField first = readFlowTruth(dir, firstFrame);
    setup.width = first.width;
    setup.height = first.height;
    result.datasetDir = dir;
    result.method = options.method == FlowMethod::Files ? "flow files read from " + options.flowDir
                                                        : flowMethodDescription(options.method);
    result.width = setup.width;
    result.height = setup.height;
    result.masks = setup.masks;
    if (setup.semantic)
        for (const char* name : kClassGroups) result.classes.push_back({name, 0, 0, {}});
    if (setup.depth)
        for (DistanceBand& band : distanceBands(options.bandEdgesMetres))
            result.bands.push_back({std::move(band.name), band.minMetres, band.maxMetres, {}});
    return setup;
}

// One log line of the headline metrics (and the method's time, which never goes into a file).
std::string summaryLine(const FlowEvaluation& e) {
    const FlowMetrics all = e.total.all.metrics();
    std::string line = e.datasetDir + ": " + std::to_string(e.frames.size()) + " frames, EPE " + fixed(all.epe, 3) +
                       " px, Fl-all " + percent(all.fl);
    if (e.masks) line += ", noc EPE " + fixed(e.total.noc.metrics().epe, 3) + " px";
    if (e.flowSeconds > 0) line += "; " + fixed(e.flowSeconds / double(e.frames.size()), 3) + " s per frame";
    return line;
}

} // namespace

FlowEvaluation runFlowEvaluation(const FlowEvaluationOptions& options) {
    requireOptions(options);
    const std::vector<uint32_t> frames = framesToEvaluate(options);
    FlowEvaluation result;
    FlowSetup setup = prepare(options, frames.front(), result);
    const std::string outDir = options.outDir.empty() ? options.datasetDir + "/eval-flow" : options.outDir;
    // The report appears whole or not at all, in a folder locked for one writer; DATASET/eval as a link is refused.
    StagedFolder staged(outDir, "report folder", !options.outDir.empty());
    setup.pictureDir = staged.path();
    if (options.pictures) makeDirectory(setup.pictureDir + "/frames", "report folder");
    evaluateInFrameOrder<FlowFrameWork>(
        frames, options.threads, [&](uint32_t frame) { return evaluateFrame(setup, frame); },
        [&](const FlowFrameWork& work) { merge(work, result); });
    result.outDir = staged.path();
    writeFlowReport(result);
    staged.commit();
    result.outDir = outDir;
    if (options.log) {
        options.log(summaryLine(result));
        options.log("report written to " + outDir + "/report.md");
    }
    return result;
}

} // namespace sward
