#include "eval/evaluation.h"

#include "common/error.h"
#include "common/staged_folder.h"
#include "dataset/naming.h"
#include "eval/dataset_reader.h"
#include "eval/frame_batches.h"
#include "eval/frame_evaluation.h"
#include "eval/number_format.h"
#include "eval/opencv_threads.h"
#include "eval/report.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace sward {

namespace {

void requireInputs(const std::string& datasetDir, const std::string& disparitiesDir, const std::vector<double>& edges) {
    std::error_code ec;
    require(fs::is_directory(datasetDir, ec), "dataset folder '" + datasetDir + "' does not exist");
    if (!disparitiesDir.empty())
        require(fs::is_directory(disparitiesDir, ec), "disparities folder '" + disparitiesDir + "' does not exist");
    requireBandEdges(edges);
}

// The dataset's frames, restricted to options.frames; at least one.
std::vector<uint32_t> framesToEvaluate(const std::string& datasetDir, const EvaluationOptions& options) {
    std::vector<uint32_t> frames = listDatasetFrames(datasetDir);
    if (options.frames)
        std::erase_if(frames, [&](uint32_t f) { return f < options.frames->first || f >= options.frames->second; });
    require(!frames.empty(), datasetDir + ": no frames to evaluate in '" + datasetDir + "/" + kDisparityFolder + "'");
    return frames;
}

// The matcher (SGBM resolved against calib.txt, unless estimates are read from a folder) and the colour scale
// shared by estimate and truth pictures: calib.txt's vmin..vmax when given, else 0..numDisparities.
void chooseMatcher(DatasetSetup& setup, DatasetEvaluation& result) {
    if (setup.disparitiesDir.empty()) {
        setup.sgbm = resolveSgbm(setup.options->sgbm, setup.calib, setup.calib.width);
        result.sgbm = setup.sgbm;
        result.matcher = sgbmDescription(*setup.sgbm);
    } else {
        result.matcher = "disparities read from " + setup.disparitiesDir;
    }
    setup.colourLo = 0;
    setup.colourHi = setup.sgbm ? setup.sgbm->numDisparities : double(setup.calib.ndisp);
    if (setup.calib.vmax > setup.calib.vmin) {
        setup.colourLo = setup.calib.vmin;
        setup.colourHi = setup.calib.vmax;
    }
}

// Empty class groups (with semantic/ images) and distance bands, named for the report.
void addGroups(const DatasetSetup& setup, DatasetEvaluation& result) {
    if (setup.semantic)
        for (const char* name : kClassGroups) result.classes.push_back({name, 0, 0, {}});
    for (DistanceBand& band : distanceBands(setup.options->bandEdgesMetres))
        result.bands.push_back({std::move(band.name), band.minMetres, band.maxMetres, {}});
}

void merge(FrameWork& f, DatasetEvaluation& result) {
    result.frames.push_back({f.frame, f.total.metrics()});
    result.total.merge(f.total);
    if (f.nonOccluded) {
        if (!result.nonOccluded) result.nonOccluded.emplace();
        result.nonOccluded->merge(*f.nonOccluded);
    }
    for (size_t c = 0; c < f.classes.size(); ++c) result.classes[c].accumulator.merge(f.classes[c]);
    for (size_t b = 0; b < f.bands.size(); ++b) result.bands[b].accumulator.merge(f.bands[b]);
    result.matchSeconds += f.matchSeconds;
}

void evaluateFrames(const DatasetSetup& setup, const std::vector<uint32_t>& frames, DatasetEvaluation& result) {
    evaluateInFrameOrder<FrameWork>(
        frames, setup.options->threads, [&](uint32_t frame) { return evaluateFrame(setup, frame); },
        [&](FrameWork& f) { merge(f, result); });
}

void requireRunOptions(const EvaluationOptions& options) {
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
}

// One log line of a dataset's headline metrics (and SGBM time, which never goes into a file).
std::string summaryLine(const DatasetEvaluation& d) {
    StereoMetrics t = d.total.metrics();
    std::string line = d.datasetDir + ": " + std::to_string(d.frames.size()) + " frames, mean |e| " +
                       fixed(t.meanAbsError, 3) + " px, mean e " + fixed(t.meanError, 3) + " px, bad-2 " +
                       percent(t.bad[2]) + ", D1 " + percent(t.d1) + ", coverage " + percent(t.coverage);
    if (d.sgbm) line += "; SGBM " + fixed(d.matchSeconds / double(d.frames.size()), 3) + " s per frame";
    return line;
}

} // namespace

DatasetEvaluation evaluateDataset(const std::string& datasetDir, const std::string& disparitiesDir,
                                  const EvaluationOptions& options, const std::string& pictureDir) {
    requireInputs(datasetDir, disparitiesDir, options.bandEdgesMetres);
    DatasetSetup setup;
    setup.dir = datasetDir;
    setup.disparitiesDir = disparitiesDir;
    setup.pictureDir = pictureDir;
    setup.options = &options;
    setup.calib = readMiddleburyCalib(datasetDir + "/" + kCalibFile);
    std::error_code ec;
    setup.semantic = fs::is_directory(datasetDir + "/" + kSemanticFolder, ec);
    setup.occlusion = fs::is_directory(datasetDir + "/" + kOcclusionFolder, ec);
    const std::vector<uint32_t> frames = framesToEvaluate(datasetDir, options);

    DatasetEvaluation result;
    result.datasetDir = datasetDir;
    result.calib = setup.calib;
    result.width = setup.calib.width;
    result.height = setup.calib.height;
    chooseMatcher(setup, result);
    if (options.pictures) makeDirectory(pictureDir + "/frames", "report folder");
    if (options.saveDisparities && setup.sgbm) makeDirectory(pictureDir + "/disparity", "report folder");
    addGroups(setup, result);
    evaluateFrames(setup, frames, result);
    return result;
}

EvaluationReport runEvaluation(const EvaluationOptions& options) {
    requireRunOptions(options);
    EvaluationReport report;
    const std::string outDir = options.outDir.empty() ? options.datasetDir + "/eval" : options.outDir;
    // The report appears whole or not at all, in a folder locked for one writer; DATASET/eval as a link is refused.
    StagedFolder staged(outDir, "report folder", !options.outDir.empty());
    report.outDir = staged.path();
    auto log = [&](const std::string& line) {
        if (options.log) options.log(line);
    };
    report.main = evaluateDataset(options.datasetDir, options.disparitiesDir, options, report.outDir);
    log(summaryLine(report.main));
    if (!options.againstDir.empty()) {
        const std::string againstOut = report.outDir + "/against";
        if (options.pictures || options.saveDisparities) makeDirectory(againstOut, "report folder");
        report.against = evaluateDataset(options.againstDir, options.againstDisparitiesDir, options, againstOut);
        log(summaryLine(*report.against));
    }
    writeReport(report);
    staged.commit();
    report.outDir = outDir;
    log("report written to " + report.outDir + "/report.md");
    return report;
}

} // namespace sward
