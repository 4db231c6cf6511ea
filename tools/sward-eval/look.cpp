// sward-eval look: the realism instrument, statistics of a sward dataset's previews per region, optionally against
// a folder of real photographs. Parses the command line and runs the measurement (eval/look.h); nothing else.
#include "eval/look.h"

#include "tools/sward-eval/commands.h"
#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <utility>

int lookMain(int argc, char** argv) {
    CLI::App app{"sward-eval look: realism statistics of a sward dataset's previews per region (colour, gradients, "
                 "Laplacian pyramid, spectrum, keypoints, texture), optionally against real photographs"};
    app.name("sward-eval look"); // the usage line names the command, not the binary's path
    sward::LookOptions options;
    bool noPictures = false;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render")->required();
    app.add_option("--reference", options.referenceDir,
                   "Folder of real photographs (*.png, *.jpg), with an optional regions.json");
    app.add_option("--out,-o", options.outDir, "Report folder (default: DATASET/eval-look)");
    sward::addParsed(app, "--frames", options.frames, "Frame range A:B (frames A .. B-1); default: all", "A:B",
                     [](const std::string& text, const std::string& flag) {
                         const auto [first, end] = sward::parseHalfOpenRange(text, 0, sward::kFrameLimit, flag);
                         return std::pair<uint32_t, uint32_t>(uint32_t(first), uint32_t(end));
                     });
    sward::addUnsigned(app, "--threads", options.threads, 0, sward::kMaxThreadsOption,
                       "Images measured at once (default 0: all cores)");
    app.add_flag("--no-pictures", noPictures, "Skip the PNG plots");
    return sward::runTool(app, argc, argv, "sward-eval", [&] {
        options.pictures = !noPictures;
        options.log = [](const std::string& line) { std::fprintf(stderr, "sward-eval: %s\n", line.c_str()); };
        sward::runLook(options);
        return 0;
    });
}
