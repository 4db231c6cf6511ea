// sward-export: a sward dataset in the layouts other tools read. Parses the command line and runs the export.
#include "common/parse_number.h"
#include "export/export.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"sward-export: rewrite a sward dataset as Middlebury / ETH3D / KITTI stereo pairs, PLY point clouds, "
                 "a COLMAP model, a nerfstudio transforms.json, a ROS 2 bag (MCAP) or SemanticKITTI LiDAR sequences"};
    sward::ExportOptions options;
    app.add_option("dataset", options.datasetDir, "Dataset folder written by sward-render")->required();
    app.add_option("--out,-o", options.outDir, "Output folder (created if missing)")->required();
    sward::addParsed(app, "--layout", options.layout,
                     "middlebury, eth3d, kitti, ply, colmap, nerfstudio, ros2 or semantickitti", "LAYOUT",
                     [](const std::string& text, const std::string& flag) { return sward::parseExportLayout(text, flag); })
        ->required();
    sward::addFrameRange(app, options.frames, "Frame range A:B (frames A .. B-1); default: all rendered");
    sward::addParsed(app, "--point-frame", options.pointFrame, "PLY coordinates: world (default) or camera",
                     "world|camera",
                     [](const std::string& text, const std::string& flag) { return sward::parsePointFrame(text, flag); });
    sward::addParsed(app, "--labels", options.labels,
                     "Class ids of the ply and semantickitti layouts: sward (default), rellis (RELLIS-3D), rugd or goose",
                     "sward|rellis|rugd|goose",
                     [](const std::string& text, const std::string& flag) { return sward::parseLabelOntology(text, flag); });
    return sward::runTool(app, argc, argv, "sward-export", [&] {
        const uint32_t frames = sward::runExport(options);
        std::printf("sward-export: %u frame(s) of %s -> %s\n", frames, options.datasetDir.c_str(), options.outDir.c_str());
        return 0;
    });
}
