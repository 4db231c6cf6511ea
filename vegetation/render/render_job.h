// The offline render job behind sward-render: load a scene, render it, write EXR/PNG files.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace sward {

struct RenderJobOptions {
    std::string scenePath;  // empty = built-in default scene
    std::string outDir = "out";
    std::optional<std::string> resolution;  // "WxH", overrides the scene
    std::optional<uint32_t> samples;        // 1 or 4, overrides the scene
    std::string device;                     // device name filter
    std::optional<glm::dvec3> cameraPosition, cameraLookAt; // absolute world positions, override the scene
    std::optional<double> fovYDegrees;
    bool validation = false;
    bool noVegetation = false;              // bare ground (same scene otherwise)
    double time = 0.0;                      // simulation time of the frame, seconds
};

// Runs the job; throws sward::Error with a one-line message on bad input or failure. Writes
// <out>/left/000000.exr, <out>/depth/000000.exr and <out>/preview/000000.png.
void runRenderJob(const RenderJobOptions& options);

} // namespace sward
