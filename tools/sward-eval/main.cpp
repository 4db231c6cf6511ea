// sward-eval: stereo evaluation of a sward dataset. Parses the command line and runs the evaluation; nothing else.
#include "common/error.h"
#include "eval/evaluation.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <sstream>

namespace {

std::pair<uint32_t, uint32_t> parseFrameRange(const std::string& text) {
    unsigned long a = 0, b = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%lu:%lu%c", &a, &b, &extra) != 2 || a >= b || b > 1000000)
        throw sward::Error("bad --frames '" + text + "': expected A:B with A < B (frames A .. B-1)");
    return {uint32_t(a), uint32_t(b)};
}

std::vector<double> parseBands(const std::string& text) {
    std::vector<double> edges;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        char* end = nullptr;
        double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0')
            throw sward::Error("bad --bands '" + text + "': expected metres like 5,10,20");
        edges.push_back(v);
    }
    return edges;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"sward-eval: stereo matching error of a sward dataset against its ground-truth disparity"};
    sward::EvaluationOptions options;
    sward::SgbmOptions& sgbm = options.sgbm;
    std::string mode = "sgbm", frames, bands;
    std::optional<int> numDisparities;
    bool noPictures = false;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render")->required();
    app.add_option("--out,-o", options.outDir, "Report folder (default: DATASET/eval)");
    app.add_option("--disparities", options.disparitiesDir,
                   "Evaluate another matcher's NNNNNN.pfm or KITTI NNNNNN.png files instead of running SGBM");
    app.add_option("--against", options.againstDir, "Second dataset evaluated the same way, reported side by side");
    app.add_option("--against-disparities", options.againstDisparitiesDir,
                   "Estimates for the --against dataset (with --disparities)");
    app.add_option("--mode", mode, "SGBM mode: sgbm, hh, 3way or hh4")->capture_default_str();
    app.add_option("--block-size", sgbm.blockSize, "SGBM block size (odd)")->capture_default_str();
    app.add_option("--num-disparities", numDisparities, "SGBM numDisparities (default: calib.txt ndisp, x16)");
    app.add_option("--p1", sgbm.p1, "SGBM P1 (default 8*cn*block^2)");
    app.add_option("--p2", sgbm.p2, "SGBM P2 (default 32*cn*block^2)");
    app.add_option("--uniqueness", sgbm.uniquenessRatio, "SGBM uniqueness ratio in percent")->capture_default_str();
    app.add_option("--speckle-window", sgbm.speckleWindowSize, "SGBM speckle window size (0: off)")
        ->capture_default_str();
    app.add_option("--speckle-range", sgbm.speckleRange, "SGBM speckle range")->capture_default_str();
    app.add_option("--disp12-max-diff", sgbm.disp12MaxDiff, "SGBM left-right check tolerance (negative: off)")
        ->capture_default_str();
    app.add_flag("--gray", sgbm.gray, "Match grey images instead of colour");
    app.add_option("--frames", frames, "Frame range A:B (frames A .. B-1); default: all");
    app.add_option("--bands", bands, "Distance band edges in metres, e.g. 5,10,20,50");
    app.add_option("--threads", options.threads, "Frames matched at once (default: all cores)");
    app.add_flag("--no-pictures", noPictures, "Skip the per-frame disparity and difference PNGs");
    app.add_flag("--save-disparities", options.saveDisparities, "Also write SGBM estimates as OUT/disparity/*.pfm");
    return sward::runTool(app, argc, argv, "sward-eval", [&] {
        sgbm.mode = sward::parseSgbmMode(mode);
        sgbm.numDisparities = numDisparities;
        if (!frames.empty()) options.frames = parseFrameRange(frames);
        if (!bands.empty()) options.bandEdgesMetres = parseBands(bands);
        options.pictures = !noPictures;
        options.log = [](const std::string& line) { std::fprintf(stderr, "sward-eval: %s\n", line.c_str()); };
        sward::runEvaluation(options);
        return 0;
    });
}
