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
    app.add_option("--wheel-radius", d.wheelRadius, "Wheel radius, metres")->capture_default_str();
    app.add_option("--wheel-width", d.wheelWidth, "Wheel width, metres")->capture_default_str();
    app.add_option("--wheel-base", d.wheelBase, "Front to rear axle, metres")->capture_default_str();
    app.add_option("--track-width", d.trackWidth, "Left to right wheel centre, metres")->capture_default_str();
    app.add_option("--baseline", d.cameraBaseline, "Stereo head lens spacing, metres")->capture_default_str();
    return sward::runTool(app, argc, argv, "sward-rover", [&] {
        sward::saveRoverGltf(out, d);
        std::printf("sward-rover: wrote %s\n", out.c_str());
        return 0;
    });
}
