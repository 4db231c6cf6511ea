// sward-eval odometry: stereo visual odometry of a sward dataset against its ground-truth poses. Parses the command
// line and runs the evaluation (eval/odometry.h); nothing else.
#include "eval/odometry.h"
#include "common/error.h"

#include "tools/sward-eval/commands.h"
#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <sstream>
#include <utility>
#include <vector>

namespace {

std::vector<double> parseLengths(const std::string& text, const std::string& flag) {
    std::vector<double> lengths;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        lengths.push_back(sward::parseReal(item, 0.001, 1e6, flag + " '" + text + "': length (metres)"));
    sward::require(!lengths.empty(), flag + ": no length given");
    return lengths;
}

// "bare:0:20,grass:20:40": named frame ranges [A, B).
std::vector<sward::OdometrySegment> parseSegments(const std::string& text, const std::string& flag) {
    std::vector<sward::OdometrySegment> segments;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        const size_t colon = item.find(':');
        sward::require(colon != std::string::npos && colon > 0,
                       flag + " '" + item + "': expected NAME:A:B (frames A .. B-1)");
        const auto [first, end] =
            sward::parseHalfOpenRange(item.substr(colon + 1), 0, sward::kFrameLimit, flag + " '" + item + "'");
        segments.push_back({item.substr(0, colon), uint32_t(first), uint32_t(end)});
    }
    return segments;
}

} // namespace

int odometryMain(int argc, char** argv) {
    CLI::App app{"sward-eval odometry: stereo visual odometry of a sward dataset against its ground-truth poses"};
    app.name("sward-eval odometry"); // the usage line names the command, not the binary's path
    sward::OdometryOptions options;
    std::string detector = "orb", matcher = "descriptors";
    bool noPictures = false;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render (stereo rig)")->required();
    app.add_option("--out,-o", options.outDir, "Report folder (default: DATASET/eval-odometry)");
    sward::addChecked(app, "--detector", detector, "Features: orb, akaze or sift", "NAME",
                      [](const std::string& text) { sward::parseDetector(text); });
    sward::addChecked(
        app, "--matcher", matcher,
        "descriptors, or truth: correspondences from the ground-truth depth and poses (a perfect matcher)", "NAME",
        [](const std::string& text) {
            sward::require(text == "descriptors" || text == "truth",
                           "unknown matcher '" + text + "' (expected descriptors or truth)");
        });
    app.add_option("--poses", options.posesFile,
                   "Evaluate this KITTI pose file (12 numbers per line, left camera-to-world, one line per frame) "
                   "instead of running the odometry");
    sward::addParsed(app, "--frames", options.frames, "Frame range A:B (frames A .. B-1); default: all", "A:B",
                     [](const std::string& text, const std::string& flag) {
                         const auto [first, end] = sward::parseHalfOpenRange(text, 0, sward::kFrameLimit, flag);
                         return std::pair<uint32_t, uint32_t>(uint32_t(first), uint32_t(end));
                     });
    sward::addParsed(app, "--lengths", options.lengthsMetres, "Relative-error sub-sequence lengths in metres",
                     "M,M,...", parseLengths);
    sward::addParsed(app, "--segments", options.segments,
                     "Frame ranges reported on their own, e.g. bare:0:20,grass:20:40", "NAME:A:B,...", parseSegments);
    sward::addReal(app, "--max-step", options.maxStepMetres, 0.001, 1e6,
                   "A motion moving the camera farther than this between two frames fails (metres, default 2)");
    sward::addReal(
        app, "--max-turn", options.maxTurnDegrees, 0.001, 180,
        "A motion turning the camera more than this between two frames fails (degrees; default: the horizontal "
        "field of view of calib.txt)");
    sward::addUnsigned(app, "--threads", options.threads, 0, sward::kMaxThreadsOption,
                       "Frames processed at once (default 0: all cores)");
    app.add_flag("--no-pictures", noPictures, "Skip the PNG plots");
    return sward::runTool(app, argc, argv, "sward-eval", [&] {
        options.detector = sward::parseDetector(detector);
        options.truthMatcher = matcher == "truth";
        sward::require(options.posesFile.empty() || !options.truthMatcher,
                       "--poses and --matcher truth exclude each other");
        options.pictures = !noPictures;
        options.log = [](const std::string& line) { std::fprintf(stderr, "sward-eval: %s\n", line.c_str()); };
        sward::runOdometry(options);
        return 0;
    });
}
