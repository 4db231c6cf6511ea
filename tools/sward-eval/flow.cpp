// sward-eval flow: optical-flow evaluation of a sward dataset. Parses the command line and runs the evaluation;
// nothing else.
#include "eval/flow_evaluation.h"
#include "eval/splits.h"

#include "tools/sward-eval/commands.h"
#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

int flowMain(int argc, char** argv) {
    CLI::App app{"sward-eval flow: optical-flow error of a sward dataset against its ground-truth forward flow"};
    app.name("sward-eval flow"); // the usage line names the command, not the binary's path
    sward::FlowEvaluationOptions options;
    std::string method = "dis";
    bool noPictures = false;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render with render.flow")
        ->required();
    app.add_option("--out,-o", options.outDir, "Report folder (default: DATASET/eval-flow)");
    CLI::Option* methodOption =
        sward::addChecked(app, "--method", method,
                          "Flow method: dis (= dis-medium), dis-ultrafast, dis-fast, dis-medium, farneback or files",
                          "METHOD", [](const std::string& text) { sward::parseFlowMethod(text); });
    app.add_option("--flow", options.flowDir,
                   "Evaluate another method's forward flow NNNNNN.flo or KITTI NNNNNN.png files (method 'files')");
    sward::addFrameRange(app, options.frames, "Frame range A:B (frames A .. B-1); default: all");
    sward::addParsed(app, "--bands", options.bandEdgesMetres, "Distance band edges in metres, e.g. 5,10,20,50",
                     "M,M,...", sward::parseBandEdges);
    sward::addUnsigned(app, "--threads", options.threads, 0, sward::kMaxThreadsOption,
                       "Frames evaluated at once (default 0: all cores)");
    app.add_flag("--no-pictures", noPictures, "Skip the per-frame flow and end-point error PNGs");
    return sward::runTool(app, argc, argv, "sward-eval flow", [&] {
        // --flow alone means method "files"; with an explicit other method the library refuses the mix.
        if (!options.flowDir.empty() && methodOption->count() == 0) method = "files";
        options.method = sward::parseFlowMethod(method);
        options.pictures = !noPictures;
        options.log = [](const std::string& line) { std::fprintf(stderr, "sward-eval flow: %s\n", line.c_str()); };
        sward::runFlowEvaluation(options);
        return 0;
    });
}
