// The closed-loop half of the Python bindings (docs/python.md, "Drive and record"): the camera keys of render()'s
// frames, the episode recorder (render/episode_recorder.h) and the vehicle controller (render/session.h drive).
#pragma once

#include "render/render_job.h"
#include "render/session.h"

#include <pybind11/pybind11.h>

namespace sward {

// Adds the frame's "tick", "time", "left_pose" (4x4 camera-to-world, OpenCV axes), "right_pose" and "baseline" (a
// stereo rig), "intrinsics" {fx, fy, cx, cy, width, height} and "record" (its frames.jsonl line as a dict) to `d`.
void addFrameRecord(pybind11::dict& d, const SessionFrame& frame);

// The render job's options for the scene a Python call names: its file (or its text), overrides, seed, asset
// folders, vegetation and start time. The caller adds what the call does with it (write_dataset, record).
RenderJobOptions sceneJobOptions(const std::string& path, const std::optional<std::string>& text,
                                 const std::string& overrides, std::optional<uint64_t> seed,
                                 const std::vector<std::string>& allowAssets, bool vegetation, double time);

// _sward.EpisodeRecorder and _sward.drive (bindSession's Session must be bound first).
void bindRecorder(pybind11::module_& m);

} // namespace sward
