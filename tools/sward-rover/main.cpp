// sward-rover: writes the default rover model (glTF 2.0, buffer embedded). Parses the command line and calls
// saveRoverGltf(); nothing else. The shipped examples/assets/rover.gltf is this tool's output with defaults:
//   sward-rover --out examples/assets/rover.gltf
#include "common/error.h"
#include "scene/rover_model.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"sward-rover: write the default four-wheeled skid-steer rover as glTF 2.0 (deterministic bytes)"};
    std::string out;
    sward::RoverDimensions d;
    app.add_option("--out,-o", out, "Output .gltf file (buffer embedded as a base64 data URI)")->required();
    sward::addReal(app, "--wheel-radius", d.wheelRadius, 0.001, 100.0, "Wheel radius, metres");
    sward::addReal(app, "--wheel-width", d.wheelWidth, 0.001, 100.0, "Wheel width, metres");
    sward::addReal(app, "--wheel-base", d.wheelBase, 0.001, 100.0, "Front to rear axle, metres");
    sward::addReal(app, "--track-width", d.trackWidth, 0.001, 100.0, "Left to right wheel centre, metres");
    sward::addReal(app, "--baseline", d.cameraBaseline, 0.001, 100.0, "Stereo head lens spacing, metres");
    return sward::runTool(app, argc, argv, "sward-rover", [&] {
        sward::saveRoverGltf(out, d);
        std::printf("sward-rover: wrote %s\n", out.c_str());
        return 0;
    });
}
