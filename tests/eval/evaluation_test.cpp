// End to end: synthetic datasets of known disparity through the evaluation library and the sward-eval executable.
#include "eval/evaluation.h"
#include "stereo_test_files.h"

#include "common/error.h"
#include "io/image_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>

using namespace sward;
using sward::test::readFile;
using sward::test::SyntheticDataset;
using sward::test::tempDir;
using sward::test::writeSyntheticDataset;

namespace {

const char* kRequiredKeys[] = {"frames", "mean_abs_error", "mean_error", "std_error", "rms",
                               "bad_1",  "bad_2",          "d1_all",     "coverage"};

nlohmann::json readJson(const std::string& path) {
    return nlohmann::json::parse(readFile(path));
}

void expectMetricKeys(const nlohmann::json& j, const std::string& where) {
    for (const char* key : kRequiredKeys) EXPECT_TRUE(j.contains(key)) << where << " lacks " << key;
    for (const char* key : {"coverage", "bad_1", "bad_2", "d1_all"}) {
        ASSERT_TRUE(j[key].is_number()) << where << " " << key;
        EXPECT_GE(j[key].get<double>(), 0.0) << where << " " << key;
        EXPECT_LE(j[key].get<double>(), 1.0) << where << " " << key;
    }
}

struct RunResult {
    int exitCode = -1;
    std::string err;
};

RunResult runEval(const std::string& args) {
    const std::string errFile = tempDir("_stderr") + "/err.txt";
    const std::string command = std::string(SWARD_EVAL_EXE) + " " + args + " >/dev/null 2>" + errFile;
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(errFile)};
}

EvaluationOptions quietOptions(const std::string& dataset, const std::string& out) {
    EvaluationOptions options;
    options.datasetDir = dataset;
    options.outDir = out;
    options.threads = 2;
    return options;
}

} // namespace

TEST(Evaluation, SgbmRecoversAKnownConstantDisparity) {
    const std::string dir = tempDir();
    SyntheticDataset s;
    writeSyntheticDataset(dir, s);
    EvaluationReport report = runEvaluation(quietOptions(dir, ""));
    ASSERT_EQ(report.main.frames.size(), s.frames);
    const StereoMetrics m = report.main.total.metrics();
    EXPECT_EQ(m.gtPixels, uint64_t(s.frames) * s.width * (s.height - s.skyRows)); // sky rows are not evaluated
    EXPECT_LT(m.meanAbsError, 0.25);
    EXPECT_LT(std::abs(m.meanError), 0.1);
    EXPECT_LT(m.bad[2], 0.02);
    // SGBM cannot match the left numDisparities columns, so coverage is well below 1 but above the rest.
    EXPECT_GT(m.coverage, 0.6);
    EXPECT_LT(m.coverage, 1.0 - 32.0 / s.width + 0.01);

    // The report went to the default folder DIR/eval.
    const std::string out = dir + "/eval";
    const nlohmann::json j = readJson(out + "/metrics.json");
    expectMetricKeys(j, "metrics.json");
    EXPECT_EQ(j["frames"], s.frames);
    EXPECT_DOUBLE_EQ(j["mean_abs_error"].get<double>(), m.meanAbsError);
    ASSERT_EQ(j["per_frame"].size(), s.frames);
    for (const auto& frame : j["per_frame"]) expectMetricKeys(frame, "per_frame");
    ASSERT_TRUE(j.contains("classes"));
    EXPECT_EQ(j["classes"]["ground"]["gt_pixels"], s.frames * (s.width / 2) * (s.height - s.skyRows));
    EXPECT_EQ(j["classes"]["vegetation"]["gt_pixels"], s.frames * (s.width / 2) * (s.height - s.skyRows));
    // Depth = f * B / d = 100 px * 0.1 m / 8 px = 1.25 m: every pixel is in the first distance band.
    EXPECT_EQ(j["distance_bands"][0]["gt_pixels"], m.gtPixels);
    for (const char* file :
         {"/metrics.csv", "/report.md", "/error_histogram.png", "/error_histogram_classes.png",
          "/frames/000000_estimate.png", "/frames/000001_truth.png", "/frames/000001_difference.png"})
        EXPECT_TRUE(std::filesystem::file_size(out + file) > 0) << file;
    const std::string csv = readFile(out + "/metrics.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + s.frames + 1) << csv; // header, frames, "all"
    // The paper's difference image: 127 where the estimate is exact, 0 where there is no comparison.
    cv::Mat diff = cv::imread(out + "/frames/000000_difference.png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(diff.type(), CV_8UC1);
    EXPECT_EQ(diff.at<uint8_t>(0, 100), 0);                   // sky
    EXPECT_EQ(diff.at<uint8_t>(int(s.height) / 2, 100), 127); // textured, matched
}

TEST(Evaluation, DisparityFilesOfAnotherMatcherAreEvaluated) {
    const std::string dir = tempDir(), estimates = tempDir("_estimates");
    SyntheticDataset s;
    writeSyntheticDataset(dir, s);
    // A "matcher" that is always 1 px too far and leaves the left 20 columns empty, in KITTI format.
    for (uint32_t frame = 0; frame < s.frames; ++frame) {
        std::vector<float> d(size_t(s.width) * s.height);
        for (uint32_t y = 0; y < s.height; ++y)
            for (uint32_t x = 0; x < s.width; ++x) d[size_t(y) * s.width + x] = x < 20 ? 0.0f : s.disparity + 1.0f;
        writeKittiPng(estimates + "/00000" + std::to_string(frame) + ".png", s.width, s.height, d);
    }
    EvaluationOptions options = quietOptions(dir, tempDir("_out"));
    options.disparitiesDir = estimates;
    const StereoMetrics m = runEvaluation(options).main.total.metrics();
    EXPECT_DOUBLE_EQ(m.meanError, 1.0);
    EXPECT_DOUBLE_EQ(m.bad[0], 1.0);
    EXPECT_DOUBLE_EQ(m.bad[1], 0.0);
    EXPECT_DOUBLE_EQ(m.coverage, double(s.width - 20) / s.width);
}

TEST(Evaluation, OcclusionMasksGiveNonOccludedMetricsBesideAllPixels) {
    const std::string dir = tempDir(), estimates = tempDir("_estimates"), out = tempDir("_out");
    SyntheticDataset s;
    writeSyntheticDataset(dir, s);
    // The estimate is exact except in the left 30 columns (5 px off); the masks call those columns occluded.
    std::filesystem::create_directories(dir + "/occlusion");
    for (uint32_t frame = 0; frame < s.frames; ++frame) {
        std::vector<float> d(size_t(s.width) * s.height);
        std::vector<uint8_t> mask(d.size());
        for (uint32_t y = 0; y < s.height; ++y)
            for (uint32_t x = 0; x < s.width; ++x) {
                d[size_t(y) * s.width + x] = float(s.disparity + (x < 30 ? 5 : 0));
                mask[size_t(y) * s.width + x] = y < s.skyRows ? 0 : x < 30 ? 128 : 255;
            }
        writePfm(estimates + "/00000" + std::to_string(frame) + ".pfm", s.width, s.height, d);
        writePng8(dir + "/occlusion/00000" + std::to_string(frame) + ".png", s.width, s.height, 1, mask);
    }
    EvaluationOptions options = quietOptions(dir, out);
    options.disparitiesDir = estimates;
    const EvaluationReport report = runEvaluation(options);
    ASSERT_TRUE(report.main.nonOccluded.has_value());
    const StereoMetrics all = report.main.total.metrics(), noc = report.main.nonOccluded->metrics();
    EXPECT_DOUBLE_EQ(noc.meanAbsError, 0.0);
    EXPECT_DOUBLE_EQ(all.meanAbsError, 5.0 * 30 / s.width);
    const nlohmann::json json = readJson(out + "/metrics.json");
    EXPECT_EQ(json.at("noc").at("mean_abs_error").get<double>(), 0.0);
    EXPECT_EQ(json.at("gt_pixels").get<int64_t>(), int64_t(s.frames) * s.width * (s.height - s.skyRows));
    EXPECT_EQ(json.at("noc").at("gt_pixels").get<int64_t>(), int64_t(s.frames) * (s.width - 30) * (s.height - s.skyRows));
    EXPECT_NE(readFile(out + "/metrics.csv").find("\nmain,noc,"), std::string::npos);
    EXPECT_NE(readFile(out + "/report.md").find("## Non-occluded pixels (noc)"), std::string::npos);
}

TEST(Evaluation, SavedSgbmDisparitiesReEvaluateToTheSameMetrics) {
    const std::string dir = tempDir(), out = tempDir("_out"), out2 = tempDir("_out2");
    writeSyntheticDataset(dir, SyntheticDataset{});
    EvaluationOptions options = quietOptions(dir, out);
    options.saveDisparities = true;
    options.pictures = false;
    const StereoMetrics first = runEvaluation(options).main.total.metrics();
    EvaluationOptions again = quietOptions(dir, out2);
    again.disparitiesDir = out + "/disparity";
    const StereoMetrics second = runEvaluation(again).main.total.metrics();
    EXPECT_EQ(first.estimatedPixels, second.estimatedPixels);
    EXPECT_EQ(first.meanError, second.meanError);
    EXPECT_EQ(first.bad, second.bad);
    EXPECT_FALSE(std::filesystem::exists(out + "/frames")); // pictures were switched off
}

TEST(Evaluation, AgainstReportsBothDatasetsAndTheirDifference) {
    const std::string a = tempDir("_a"), b = tempDir("_b"), out = tempDir("_out");
    writeSyntheticDataset(a, SyntheticDataset{});
    SyntheticDataset flat;
    flat.disparity = 5;
    flat.seed = 7;
    writeSyntheticDataset(b, flat);
    EvaluationOptions options = quietOptions(a, out);
    options.againstDir = b;
    EvaluationReport report = runEvaluation(options);
    ASSERT_TRUE(report.against);
    const nlohmann::json j = readJson(out + "/metrics.json");
    ASSERT_TRUE(j.contains("against"));
    expectMetricKeys(j["against"], "against");
    EXPECT_EQ(j["against"]["per_frame"].size(), 2u);
    EXPECT_EQ(j["against"]["dataset"], b);
    ASSERT_TRUE(j.contains("difference"));
    EXPECT_DOUBLE_EQ(j["difference"]["coverage"].get<double>(),
                     j["coverage"].get<double>() - j["against"]["coverage"].get<double>());
    EXPECT_TRUE(std::filesystem::exists(out + "/against/frames/000000_estimate.png"));
    const std::string md = readFile(out + "/report.md");
    EXPECT_NE(md.find("| difference |"), std::string::npos);
    EXPECT_NE(md.find(b), std::string::npos);
}

TEST(Evaluation, OutputIsBitwiseIdenticalWithOneOrTwoThreads) {
    const std::string dir = tempDir(), one = tempDir("_one"), two = tempDir("_two");
    SyntheticDataset s;
    s.frames = 3;
    writeSyntheticDataset(dir, s);
    EvaluationOptions options = quietOptions(dir, one);
    options.threads = 1;
    runEvaluation(options);
    options.outDir = two;
    options.threads = 2;
    runEvaluation(options);
    for (const char* file :
         {"/metrics.json", "/metrics.csv", "/report.md", "/error_histogram.png", "/frames/000002_estimate.png"}) {
        const std::string reference = readFile(one + file);
        ASSERT_FALSE(reference.empty()) << file;
        EXPECT_TRUE(reference == readFile(two + file)) << file << " differs between 1 and 2 threads";
    }
}

TEST(Evaluation, MismatchedCalibrationIsOneClearError) {
    const std::string dir = tempDir();
    writeSyntheticDataset(dir, SyntheticDataset{});
    StereoCalib calib = readMiddleburyCalib(dir + "/calib.txt");
    calib.width = 640;
    writeMiddleburyCalib(dir + "/calib.txt", calib);
    try {
        runEvaluation(quietOptions(dir, ""));
        FAIL() << "accepted a calib.txt of the wrong size";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("calib.txt"), std::string::npos) << e.what();
    }
}

TEST(Evaluation, AFailedRunLeavesAnEarlierReportAsItWasAndNothingBeside) {
    const std::string dir = tempDir();
    writeSyntheticDataset(dir, SyntheticDataset{});
    const std::string out = dir + "/report";
    runEvaluation(quietOptions(dir, out));
    const std::string before = readFile(out + "/metrics.json");
    // The last frame's ground truth is cut short: the run fails after the first frames' pictures were made.
    const std::string last = dir + "/disparity/000001.pfm";
    std::filesystem::resize_file(last, std::filesystem::file_size(last) / 2);
    EXPECT_THROW(runEvaluation(quietOptions(dir, out)), Error);
    EXPECT_EQ(readFile(out + "/metrics.json"), before);
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".report.sward-"), std::string::npos) << entry.path();
    // A report folder that did not exist is not created by a failed run.
    EXPECT_THROW(runEvaluation(quietOptions(dir, dir + "/new/report")), Error);
    EXPECT_FALSE(std::filesystem::exists(dir + "/new"));
}

TEST(Evaluation, AgainstNeedsEstimatesForBothDatasetsOrNeither) {
    const std::string a = tempDir("_a"), b = tempDir("_b");
    writeSyntheticDataset(a, SyntheticDataset{});
    writeSyntheticDataset(b, SyntheticDataset{});
    EvaluationOptions options = quietOptions(a, tempDir("_out"));
    options.againstDir = b;
    options.disparitiesDir = a + "/disparity"; // the ground truth as a "perfect matcher" for `a` only
    EXPECT_THROW(runEvaluation(options), Error);
    options.againstDisparitiesDir = b + "/disparity";
    const EvaluationReport report = runEvaluation(options);
    EXPECT_DOUBLE_EQ(report.main.total.metrics().meanAbsError, 0.0);
    EXPECT_DOUBLE_EQ(report.against->total.metrics().coverage, 1.0);
}

TEST(SwardEval, ExecutableWritesTheReport) {
    const std::string dir = tempDir(), out = tempDir("_out");
    writeSyntheticDataset(dir, SyntheticDataset{});
    RunResult r = runEval("'" + dir + "' --out '" + out + "' --mode 3way --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = readJson(out + "/metrics.json");
    expectMetricKeys(j, "metrics.json");
    EXPECT_LT(j["mean_abs_error"].get<double>(), 0.3);
    EXPECT_NE(j["matcher"].get<std::string>().find("mode 3way"), std::string::npos);
    EXPECT_NE(r.err.find("report written"), std::string::npos) << r.err;
}

TEST(SwardEval, MissingDatasetIsOneLineNamingThePath) {
    const std::string missing = tempDir() + "/no-such-dataset";
    RunResult r = runEval("'" + missing + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
}

TEST(SwardEval, UsageErrorsExitWithTwo) {
    EXPECT_EQ(runEval("").exitCode, 2); // no dataset
    EXPECT_EQ(runEval(tempDir() + " --no-such-option").exitCode, 2);
    RunResult r = runEval(tempDir() + " --mode fancy");
    EXPECT_EQ(r.exitCode, 2) << "a bad option value is a usage error (tools/tool_main.h)";
    EXPECT_NE(r.err.find("fancy"), std::string::npos) << r.err;
}

TEST(SwardEval, MissingPreviewImageIsNamed) {
    const std::string dir = tempDir();
    writeSyntheticDataset(dir, SyntheticDataset{});
    std::filesystem::remove(dir + "/preview_right/000001.png");
    RunResult r = runEval("'" + dir + "' --no-pictures");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("preview_right/000001.png"), std::string::npos) << r.err;
}
