// The offline render job behind sward-render: load a scene, render it, write EXR/PNG files.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace sward {

struct Scene;

struct RenderJobOptions {
    std::string scenePath;  // empty = built-in default scene
    std::optional<std::string> sceneText;   // the scene as JSON text instead of a file (the Python module)
    std::string overrides;                  // JSON object of dotted keys -> values (scene/scene_input.h)
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
    std::optional<std::string> shard;       // "I/N": the I-th of N contiguous blocks of the selected frames
    std::optional<uint64_t> seed;           // overrides the scene's seed (terrain, placement, gusts, noise)
    std::vector<std::string> allowAssets;   // --allow-assets: folders outside the scene's the scene may read from
    bool quiet = false;                     // no progress line even on a terminal
    bool overwrite = false;                 // --overwrite: remove the dataset already in outDir and start over
    // Called on the caller's thread before each frame renders, with how many of the run's frames to write have
    // rendered and their count, and once all are written with (total, total): the Python module's progress callback
    // and Ctrl-C check. If it throws, the run stops as on any failure (removing what it created) and the exception
    // reaches the caller.
    std::function<void(uint32_t rendered, uint32_t total)> onProgress;
};

// What a dataset of the scene `options` names carries about it, for the episode recorder (render/episode_recorder.h) to
// write what sward-render writes: scene.json's text, the fingerprint's scene hash, classes.json's text and the source
// revision the manifest records.
std::string datasetSceneText(const RenderJobOptions& options);
std::string datasetSceneHash(const RenderJobOptions& options);
std::string datasetClassesText(const Scene& scene);
std::string datasetRevision();

// Parses "A:B" (0 <= A < B <= kFrameLimit, digits only): frames A .. B-1. Throws a clear error otherwise.
void parseFrameRange(const std::string& text, uint32_t& first, uint32_t& end);

// What a run did, for the tool to print, and what it measured, for sward-bench dataset (the dataset's files hold no
// timings).
struct RenderJobReport {
    std::string summary; // one line: scene, frames rendered and skipped, size, samples, views, folder, seconds
    uint32_t width = 0, height = 0, samples = 0; // of the images rendered
    std::string device;                          // the Vulkan device's name
    struct Frame {
        double renderSeconds = 0.0; // rendering the frame and reading it back (the caller's thread)
        double waitSeconds = 0.0;   // then waiting for the previous frame's files (the writer is one frame behind)
        double writeSeconds = 0.0;  // encoding and writing its files (the writer's thread, beside the next render)
        double doneSeconds = 0.0;   // since the run started, when its files were on disk
        double cpuSeconds = 0.0; // the process's CPU time since the run started (every thread, the driver's too) then
    };
    double setupSeconds = 0.0;    // the run's start until the first frame starts to render
    double manifestSeconds = 0.0; // after the last frame: hashing every file and writing the manifest
    std::vector<Frame> frames; // per frame written, in order
};

// Runs the job; throws sward::Error with a one-line message on bad input or failure. Writes the dataset described
// in docs/dataset-format.md (dataset_writer.h). Frame i shows simulation tick i (time i * sequence.time_step;
// the wind sees options.time added). Frames whose files all exist already are skipped (resume); the interaction
// simulation still runs every tick from 0, so any frame range or shard shows exactly what a full run shows.
// Resume is safe: a folder holding a dataset of another fingerprint (dataset/fingerprint.h) is refused unless
// options.overwrite. Every check (scene, plan, device, output folder, free space for one frame) runs before the
// first byte is written, and a run that fails removes every file and folder it created. Returns what the run did
// and how long each frame took (RenderJobReport).
RenderJobReport runRenderJob(const RenderJobOptions& options);

} // namespace sward
