// sward-bench: prints benchmark figures (and writes them as JSON with --json). Thin: parsing and printing only.
#include "render/benchmarks.h"
#include "common/atomic_file.h"
#include "scene/scene.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace {

// Prints every key except `tableKey` (printed as a table by the caller) and writes the JSON file atomically.
void emit(const nlohmann::json& result, const std::string& jsonPath, const std::string& tableKey = "") {
    for (auto it = result.begin(); it != result.end(); ++it)
        if (it.key() != tableKey) std::printf("%-32s %s\n", it.key().c_str(), it.value().dump().c_str());
    if (jsonPath.empty()) return;
    sward::writeTextAtomically(jsonPath, result.dump(2) + "\n");
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"sward-bench: measured figures for sward"};
    app.require_subcommand(1);
    std::string json;
    app.add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::GenerateBenchOptions generate;
    CLI::App* gen = app.add_subcommand("generate", "Generate and upload one full tile of plants");
    gen->add_option("--density", generate.density, "Grass plants per m^2")->capture_default_str();
    gen->add_option("--tile-size", generate.tileSize, "Tile edge in metres")->capture_default_str();
    gen->add_option("--threads", generate.threads, "Worker threads (0 = all cores)")->capture_default_str();
    gen->add_option("--repeats", generate.repeats, "Generation runs (median reported)")->capture_default_str();
    gen->add_option("--device", generate.device, "Vulkan device name substring");
    gen->add_flag("!--no-upload", generate.upload, "Skip the GPU upload");
    gen->add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::FrameBenchOptions frame;
    std::string resolution = "1024x768";
    CLI::App* frm = app.add_subcommand("frame", "Render a scene and time the GPU passes and the expansion overhead");
    frm->add_option("scene", frame.scenePath, "Scene JSON (default: examples/meadow.json)");
    frm->add_option("--allow-assets", frame.allowAssets,
                    "Also read the scene's assets from this folder (repeatable; default: the scene's folder only)");
    frm->add_option("--resolution", resolution, "WIDTHxHEIGHT")->capture_default_str();
    frm->add_option("--samples", frame.samples, "MSAA samples (1 or 4)")->capture_default_str();
    frm->add_option("--frames", frame.frames, "Measured frames per figure (medians)")->capture_default_str();
    frm->add_option("--device", frame.device, "Vulkan device name substring");
    frm->add_option("--json", json, "Also write the figures as a JSON object to this file");

    sward::CollideBenchOptions collide;
    CLI::App* col = app.add_subcommand(
        "collide", "Interaction worst case: one colliding sphere per 5 x 5 m cluster of N fields (CPU collision, "
                   "upload, GPU recovery), 10,000 colliders above the grass, and no GPU work with 0 active fields");
    col->add_option("--fields", collide.fields, "Fields with colliders, one case per value (repeatable)")
        ->capture_default_str();
    col->add_option("--ticks", collide.ticks, "Measured ticks per case (medians)")->capture_default_str();
    col->add_option("--warmup", collide.warmup, "Ticks per case before measuring")->capture_default_str();
    col->add_option("--threads", collide.threads, "Collision threads (0 = all cores)")->capture_default_str();
    col->add_option("--density", collide.density, "Grass plants per m^2")->capture_default_str();
    col->add_option("--radius", collide.radius, "Collider sphere radius, metres")->capture_default_str();
    col->add_option("--device", collide.device, "Vulkan device name substring");
    col->add_flag("!--no-gpu", collide.gpu, "CPU collision only: no Vulkan device, no upload or GPU figures");
    col->add_option("--json", json, "Also write the figures as a JSON object to this file");

    return sward::runTool(app, argc, argv, "sward-bench", [&] {
        if (gen->parsed()) emit(sward::benchGenerate(generate), json);
        if (frm->parsed()) {
            sward::parseResolution(resolution, frame.width, frame.height);
            emit(sward::benchFrame(frame), json);
        }
        if (col->parsed()) {
            nlohmann::json result = sward::benchCollide(collide);
            std::fputs(sward::collideTable(result).c_str(), stdout);
            emit(result, json, "results");
        }
        return 0;
    });
}
