// sward-eval stereo: stereo evaluation of a sward dataset. Parses the command line and runs the evaluation; nothing
// else. `sward-eval DATASET` (no command word) is the stereo evaluation too.
#include "common/error.h"
#include "eval/evaluation.h"
#include "eval/splits.h"

#include "tools/sward-eval/commands.h"
#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <vector>

int stereoMain(int argc, char** argv) {
    CLI::App app{"sward-eval stereo: stereo matching error of a sward dataset against its ground-truth disparity"};
    app.name("sward-eval [stereo]"); // the usage line names the command, not the binary's path
    sward::EvaluationOptions options;
    sward::SgbmOptions& sgbm = options.sgbm;
    std::string mode = "sgbm";
    std::optional<int> numDisparities;
    bool noPictures = false;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render")->required();
    app.add_option("--out,-o", options.outDir, "Report folder (default: DATASET/eval)");
    app.add_option("--disparities", options.disparitiesDir,
                   "Evaluate another matcher's NNNNNN.pfm or KITTI NNNNNN.png files instead of running SGBM");
    app.add_option("--against", options.againstDir, "Second dataset evaluated the same way, reported side by side");
    app.add_option("--against-disparities", options.againstDisparitiesDir,
                   "Estimates for the --against dataset (with --disparities)");
    sward::addChecked(app, "--mode", mode, "SGBM mode: sgbm, hh, 3way or hh4", "MODE",
                      [](const std::string& text) { sward::parseSgbmMode(text); });
    // Ranges: OpenCV's StereoSGBM limits (eval/sgbm.cpp checks the finer rules: odd block, multiple of 16).
    sward::addInteger(app, "--block-size", sgbm.blockSize, 1, 31, "SGBM block size (odd)");
    sward::addInteger(app, "--num-disparities", numDisparities, 16, 16384,
                      "SGBM numDisparities (default: calib.txt ndisp, x16)");
    sward::addInteger(app, "--p1", sgbm.p1, 1, INT32_MAX, "SGBM P1 (default 8*cn*block^2)");
    sward::addInteger(app, "--p2", sgbm.p2, 1, INT32_MAX, "SGBM P2 (default 32*cn*block^2)");
    sward::addInteger(app, "--uniqueness", sgbm.uniquenessRatio, 0, 100, "SGBM uniqueness ratio in percent");
    sward::addInteger(app, "--speckle-window", sgbm.speckleWindowSize, 0, 1000000, "SGBM speckle window size (0: off)");
    sward::addInteger(app, "--speckle-range", sgbm.speckleRange, 0, 1000000, "SGBM speckle range");
    sward::addInteger(app, "--disp12-max-diff", sgbm.disp12MaxDiff, -1000000, 1000000,
                      "SGBM left-right check tolerance (negative: off)");
    app.add_flag("--gray", sgbm.gray, "Match grey images instead of colour");
    sward::addFrameRange(app, options.frames, "Frame range A:B (frames A .. B-1); default: all");
    sward::addParsed(app, "--bands", options.bandEdgesMetres, "Distance band edges in metres, e.g. 5,10,20,50",
                     "M,M,...", sward::parseBandEdges);
    sward::addUnsigned(app, "--threads", options.threads, 0, sward::kMaxThreadsOption,
                       "Frames matched at once (default 0: all cores)");
    app.add_flag("--no-pictures", noPictures, "Skip the per-frame disparity and difference PNGs");
    app.add_flag("--save-disparities", options.saveDisparities, "Also write SGBM estimates as OUT/disparity/*.pfm");
    return sward::runTool(app, argc, argv, "sward-eval", [&] {
        sgbm.mode = sward::parseSgbmMode(mode);
        sgbm.numDisparities = numDisparities;
        options.pictures = !noPictures;
        options.log = [](const std::string& line) { std::fprintf(stderr, "sward-eval: %s\n", line.c_str()); };
        sward::runEvaluation(options);
        return 0;
    });
}
