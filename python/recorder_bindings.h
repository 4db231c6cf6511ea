// The closed-loop half of the Python bindings (docs/python.md, "Drive and record"): the camera keys of render()'s
// frames, the episode recorder (render/episode_recorder.h) and the vehicle controller (render/session.h drive).
#pragma once

#include "render/session.h"

#include <pybind11/pybind11.h>

namespace sward {

// Adds the frame's "tick", "time", "left_pose" (4x4 camera-to-world, OpenCV axes), "right_pose" and "baseline" (a
// stereo rig), "intrinsics" {fx, fy, cx, cy, width, height} and "record" (its frames.jsonl line as a dict) to `d`.
void addFrameRecord(pybind11::dict& d, const SessionFrame& frame);

// _sward.EpisodeRecorder and _sward.drive (bindSession's Session must be bound first).
void bindRecorder(pybind11::module_& m);

} // namespace sward
