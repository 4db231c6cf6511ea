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
    double time = 0.0;                      // simulation time offset added to every frame, seconds
    std::optional<std::string> frames;      // "A:B" = frames A .. B-1; default: the scene's whole sequence
};

// Parses "A:B" (0 <= A < B): frames A .. B-1. Throws a clear error otherwise.
void parseFrameRange(const std::string& text, uint32_t& first, uint32_t& end);

// Runs the job; throws sward::Error with a one-line message on bad input or failure. Writes, per frame NNNNNN,
// <out>/left/NNNNNN.exr, <out>/depth/NNNNNN.exr and <out>/preview/NNNNNN.png. Frame i is at simulation time
// options.time + i * sequence.time_step.
void runRenderJob(const RenderJobOptions& options);

} // namespace sward
