// End to end: synthetic flow datasets of known motion through the flow evaluation library and `sward-eval flow`.
#include "eval/flow_evaluation.h"
#include "flow_test_files.h"
#include "stereo_test_files.h"

#include "common/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <utility>

using namespace sward;
using sward::test::FlowDataset;
using sward::test::readFile;
using sward::test::tempDir;
using sward::test::writeFlowDataset;
using sward::test::writeFlowEstimates;

namespace {

FlowEvaluationOptions quietOptions(const std::string& dataset, const std::string& out) {
    FlowEvaluationOptions options;
    options.datasetDir = dataset;
    options.outDir = out;
    options.threads = 2;
    return options;
}

FlowEvaluationOptions filesOptions(const std::string& dataset, const std::string& flowDir, const std::string& out) {
    FlowEvaluationOptions options = quietOptions(dataset, out);
    options.method = FlowMethod::Files;
    options.flowDir = flowDir;
    options.pictures = false;
    return options;
}

struct RunResult {
    int exitCode = -1;
    std::string err;
};

RunResult runEvalFlow(const std::string& args) {
    const std::string errFile = tempDir("_stderr") + "/err.txt";
    const std::string command = std::string(SWARD_EVAL_EXE) + " flow " + args + " >/dev/null 2>" + errFile;
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(errFile)};
}

// Every file under `dir`, relative, sorted.
std::vector<std::string> filesUnder(const std::string& dir) {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) files.push_back(std::filesystem::relative(entry.path(), dir).string());
    std::sort(files.begin(), files.end());
    return files;
}

void expectErrorNaming(const FlowEvaluationOptions& options, const std::string& what, const std::string& problem) {
    try {
        runFlowEvaluation(options);
        ADD_FAILURE() << "accepted: expected an error naming " << what;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
}

} // namespace

TEST(FlowEvaluation, DisRecoversAKnownSubPixelTranslation) {
    const std::string dir = tempDir(), out = tempDir("_out");
    const FlowDataset s;
    writeFlowDataset(dir, s);
    const FlowEvaluation e = runFlowEvaluation(quietOptions(dir, out));
    ASSERT_EQ(e.frames.size(), s.frames - 1) << "the last frame's target image does not exist";
    const FlowMetrics all = e.total.all.metrics(), noc = e.total.noc.metrics();
    EXPECT_EQ(all.gtPixels, uint64_t(s.frames - 1) * s.width * (s.height - s.skyRows));
    EXPECT_EQ(noc.gtPixels, uint64_t(s.frames - 1) * (s.width - s.occludedColumns) * (s.height - s.skyRows));
    EXPECT_DOUBLE_EQ(all.coverage, 1.0);
    EXPECT_LT(noc.epe, 0.1); // 0.036 px with OpenCV 4.6
    EXPECT_LT(all.fl, 0.01);
    EXPECT_NEAR(all.meanTruthMagnitude, std::hypot(1.5, 0.75), 1e-6);
    for (const char* file : {"metrics.json", "metrics.csv", "report.md", "frames/000000_truth.png",
                             "frames/000001_estimate.png", "frames/000001_epe.png"})
        EXPECT_GT(std::filesystem::file_size(out + "/" + file), 0u) << file;
    EXPECT_FALSE(std::filesystem::exists(out + "/frames/000002_truth.png"));
    const nlohmann::json j = nlohmann::json::parse(readFile(out + "/metrics.json"));
    EXPECT_EQ(j["frames"], 2);
    EXPECT_EQ(j["all"]["epe"].get<double>(), all.epe);
    EXPECT_EQ(j["noc"]["fl"].get<double>(), noc.fl);
    EXPECT_NE(j["method"].get<std::string>().find("DISOpticalFlow dis-medium"), std::string::npos);
    EXPECT_EQ(j["per_frame"].size(), 2u);
    EXPECT_TRUE(j["classes"].contains("vegetation"));
    EXPECT_EQ(j["distance_bands"].size(), 5u);
}

TEST(FlowEvaluation, FarnebackAndTheOtherDisPresetsRun) {
    const std::string dir = tempDir();
    FlowDataset s;
    s.frames = 2;
    writeFlowDataset(dir, s);
    for (FlowMethod method : {FlowMethod::Farneback, FlowMethod::DisFast, FlowMethod::DisUltrafast}) {
        FlowEvaluationOptions options = quietOptions(dir, tempDir("_out"));
        options.method = method;
        options.pictures = false;
        const FlowEvaluation e = runFlowEvaluation(options);
        EXPECT_LT(e.total.noc.metrics().epe, 1.0) << flowMethodName(method);
        EXPECT_NE(e.method.find(method == FlowMethod::Farneback ? "Farneback" : flowMethodName(method)),
                  std::string::npos)
            << e.method;
    }
}

TEST(FlowEvaluation, AFlowFileOffByThreeFourGivesAnEndPointErrorOfFive) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    const FlowDataset s;
    writeFlowDataset(dir, s);
    writeFlowEstimates(flow, s, [](uint32_t, uint32_t) { return std::pair{3.0f, 4.0f}; });
    const FlowEvaluation e = runFlowEvaluation(filesOptions(dir, flow, tempDir("_out")));
    const FlowMetrics all = e.total.all.metrics();
    EXPECT_DOUBLE_EQ(all.epe, 5.0);
    EXPECT_DOUBLE_EQ(all.rmsEpe, 5.0);
    EXPECT_DOUBLE_EQ(all.fl, 1.0); // 5 px > 3 px and > 5 % of |(1.5, -0.75)|
    EXPECT_DOUBLE_EQ(all.bad[0], 1.0);
    EXPECT_EQ(e.method, "flow files read from " + flow);
}

TEST(FlowEvaluation, OccludedColumnsCountInAllButNotInNoc) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    const FlowDataset s;
    writeFlowDataset(dir, s);
    const uint32_t firstOccluded = s.width - s.occludedColumns;
    writeFlowEstimates(flow, s, [&](uint32_t x, uint32_t) {
        return x >= firstOccluded ? std::pair{3.0f, 4.0f} : std::pair{0.0f, 0.0f};
    });
    const FlowEvaluation e = runFlowEvaluation(filesOptions(dir, flow, tempDir("_out")));
    EXPECT_DOUBLE_EQ(e.total.noc.metrics().epe, 0.0);
    EXPECT_DOUBLE_EQ(e.total.all.metrics().epe, 5.0 * s.occludedColumns / s.width);
    EXPECT_DOUBLE_EQ(e.total.all.metrics().fl, double(s.occludedColumns) / s.width);
}

TEST(FlowEvaluation, ErrorsSplitByClassGroupAndByDistanceBand) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    FlowDataset s;
    s.occludedColumns = 0;
    writeFlowDataset(dir, s);
    // 5 px off in the right half (vegetation), 10 px off in the bottom-left quarter (ground, near band).
    writeFlowEstimates(flow, s, [&](uint32_t x, uint32_t y) {
        if (x >= s.width / 2) return std::pair{3.0f, 4.0f};
        return y >= s.height / 2 ? std::pair{6.0f, 8.0f} : std::pair{0.0f, 0.0f};
    });
    const FlowEvaluation e = runFlowEvaluation(filesOptions(dir, flow, tempDir("_out")));
    ASSERT_EQ(e.classes.size(), 4u);
    EXPECT_EQ(e.classes[0].name, "vegetation");
    EXPECT_DOUBLE_EQ(e.classes[0].errors.all.metrics().epe, 5.0);
    EXPECT_EQ(e.classes[1].name, "ground");
    const double groundRows = s.height - s.skyRows, nearRows = s.height / 2, farRows = groundRows - nearRows;
    EXPECT_DOUBLE_EQ(e.classes[1].errors.all.metrics().epe, 10.0 * nearRows / groundRows);
    EXPECT_EQ(e.classes[2].errors.all.gtPixels(), 0u); // no object
    ASSERT_EQ(e.bands.size(), 5u);                     // 0-5, 5-10, 10-20, 20-50, 50+ m
    EXPECT_EQ(e.bands[0].name, "0-5 m");
    EXPECT_DOUBLE_EQ(e.bands[0].errors.all.metrics().epe, 7.5); // near rows: half 5 px, half 10 px
    EXPECT_DOUBLE_EQ(e.bands[3].errors.all.metrics().epe, 2.5); // far rows: half 5 px, half exact
    EXPECT_EQ(e.bands[3].errors.all.gtPixels(), uint64_t(s.frames - 1) * s.width * uint64_t(farRows));
    EXPECT_EQ(e.bands[1].errors.all.gtPixels(), 0u);
}

TEST(FlowEvaluation, KittiPngFlowFilesAreReadToo) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    const FlowDataset s;
    writeFlowDataset(dir, s);
    for (uint32_t frame = 0; frame + 1 < s.frames; ++frame) // the truth itself, in KITTI's format: a perfect method
        std::filesystem::copy_file(dir + "/flow_forward/" + frameName(frame) + ".png",
                                   flow + "/" + frameName(frame) + ".png");
    const FlowEvaluation e = runFlowEvaluation(filesOptions(dir, flow, tempDir("_out")));
    EXPECT_DOUBLE_EQ(e.total.all.metrics().epe, 0.0);
}

TEST(FlowEvaluation, EveryOutputFileIsBitwiseIdenticalWithOneOrTwoThreads) {
    const std::string dir = tempDir(), one = tempDir("_one"), two = tempDir("_two");
    FlowDataset s;
    s.frames = 4;
    writeFlowDataset(dir, s);
    FlowEvaluationOptions options = quietOptions(dir, one);
    options.threads = 1;
    runFlowEvaluation(options);
    options.outDir = two;
    options.threads = 2;
    runFlowEvaluation(options);
    const std::vector<std::string> files = filesUnder(one);
    EXPECT_EQ(files.size(), 3u + 3 * 3); // metrics.json, metrics.csv, report.md; 3 pictures of frames 0..2
    EXPECT_EQ(files, filesUnder(two));
    for (const std::string& file : files)
        EXPECT_TRUE(readFile(one + "/" + file) == readFile(two + "/" + file))
            << file << " differs between 1 and 2 threads";
}

TEST(FlowEvaluation, ADatasetWithoutFlowIsOneClearError) {
    const std::string dir = tempDir();
    writeFlowDataset(dir, FlowDataset{});
    std::filesystem::remove_all(dir + "/flow_forward");
    expectErrorNaming(quietOptions(dir, ""), dir + "/flow_forward", "\"flow\": true");
    EXPECT_FALSE(std::filesystem::exists(dir + "/eval-flow"));
}

TEST(FlowEvaluation, AMissingFileOfAFrameIsNamedAndNothingIsWritten) {
    const std::string dir = tempDir(), out = tempDir("_out") + "/report";
    FlowDataset s;
    s.frames = 4;
    writeFlowDataset(dir, s);
    std::filesystem::remove(dir + "/preview/000002.png"); // frame 1's target, frame 2's source
    expectErrorNaming(quietOptions(dir, out), "preview/000002.png", "missing");
    EXPECT_FALSE(std::filesystem::exists(out));
    writeFlowDataset(dir, s);
    std::filesystem::remove(dir + "/flow_forward_mask/000001.png");
    expectErrorNaming(quietOptions(dir, out), "flow_forward_mask/000001.png", "missing");
    writeFlowDataset(dir, s);
    std::filesystem::remove(dir + "/depth/000000.exr");
    expectErrorNaming(quietOptions(dir, out), "depth/000000.exr", "missing");
    FlowEvaluationOptions range = quietOptions(dir, out);
    range.frames = std::pair{7u, 9u};
    expectErrorNaming(range, "flow_forward", "no frames");
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(FlowEvaluation, BadUserFlowFilesAreNamedWithTheirProblem) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    FlowDataset s;
    writeFlowDataset(dir, s);
    writeFlowEstimates(flow, s, [](uint32_t, uint32_t) { return std::pair{0.0f, 0.0f}; });
    FlowDataset small = s;
    small.width = 80;
    const std::string smallDir = tempDir("_small");
    writeFlowEstimates(smallDir, small, [](uint32_t, uint32_t) { return std::pair{0.0f, 0.0f}; });
    std::filesystem::copy_file(smallDir + "/000000.flo", flow + "/000001.flo",
                               std::filesystem::copy_options::overwrite_existing);
    expectErrorNaming(filesOptions(dir, flow, ""), flow + "/000001.flo", "80x120");
    // A corrupt tag, then a file cut short.
    std::string bytes = readFile(flow + "/000000.flo");
    std::filesystem::copy_file(flow + "/000000.flo", flow + "/000001.flo",
                               std::filesystem::copy_options::overwrite_existing);
    bytes[0] = 'X';
    std::ofstream(flow + "/000000.flo", std::ios::binary | std::ios::trunc) << bytes;
    expectErrorNaming(filesOptions(dir, flow, ""), flow + "/000000.flo", "tag");
    std::ofstream(flow + "/000000.flo", std::ios::binary | std::ios::trunc) << bytes.substr(4, 100).insert(0, "PIEH");
    expectErrorNaming(filesOptions(dir, flow, ""), flow + "/000000.flo", "truncated");
    std::filesystem::remove(flow + "/000000.flo");
    expectErrorNaming(filesOptions(dir, flow, ""), flow + "/000000", "no flow for frame 000000");
    EXPECT_FALSE(std::filesystem::exists(dir + "/eval-flow"));
}

TEST(FlowEvaluation, FilesAndAFlowFolderGoTogether) {
    const std::string dir = tempDir();
    writeFlowDataset(dir, FlowDataset{});
    FlowEvaluationOptions options = quietOptions(dir, "");
    options.method = FlowMethod::Files;
    expectErrorNaming(options, "--flow", "files");
    options.method = FlowMethod::Farneback;
    options.flowDir = dir;
    expectErrorNaming(options, "--flow", "farneback");
}

TEST(SwardEvalFlow, ExecutableWritesTheReport) {
    const std::string dir = tempDir(), out = tempDir("_out");
    FlowDataset s;
    s.frames = 2;
    writeFlowDataset(dir, s);
    const RunResult r = runEvalFlow("'" + dir + "' --out '" + out + "' --method dis-fast --threads 1 --bands 3,10");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(readFile(out + "/metrics.json"));
    EXPECT_LT(j["noc"]["epe"].get<double>(), 1.0);
    EXPECT_EQ(j["distance_bands"].size(), 3u);
    EXPECT_NE(r.err.find("report written"), std::string::npos) << r.err;
    const std::string csv = readFile(out + "/metrics.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "frame,region,gt_pixels,estimated_pixels,coverage,mean_flow,epe,rms_epe,"
                                             "max_epe,bad_1,bad_3,fl");
    EXPECT_NE(csv.find("\ntotal,noc,"), std::string::npos) << csv;
}

TEST(SwardEvalFlow, FlowFolderAloneMeansMethodFiles) {
    const std::string dir = tempDir(), flow = tempDir("_flow");
    FlowDataset s;
    s.frames = 2;
    writeFlowDataset(dir, s);
    writeFlowEstimates(flow, s, [](uint32_t, uint32_t) { return std::pair{3.0f, 4.0f}; });
    const RunResult r = runEvalFlow("'" + dir + "' --flow '" + flow + "' --no-pictures");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(readFile(dir + "/eval-flow/metrics.json"));
    EXPECT_EQ(j["all"]["epe"].get<double>(), 5.0);
    EXPECT_FALSE(std::filesystem::exists(dir + "/eval-flow/frames"));
}

TEST(SwardEvalFlow, ErrorsAreOneLineAndUsageErrorsExitTwo) {
    const std::string missing = tempDir() + "/no-such-dataset";
    RunResult r = runEvalFlow("'" + missing + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
    EXPECT_EQ(runEvalFlow("").exitCode, 2);
    r = runEvalFlow(tempDir() + " --method raft");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("raft"), std::string::npos) << r.err;
    EXPECT_EQ(runEvalFlow(tempDir() + " --bands 10,5x").exitCode, 2);
}
