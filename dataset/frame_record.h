// frames.jsonl records: everything about one frame of a dataset that is not an image (docs/dataset-format.md).
// Every value is a pure function of the scene and the tick, so any process (a shard, a resumed run) writes
// the same record for the same frame.
#pragma once

#include "scene/camera_rig.h"
#include "interaction/colliders.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

class Ground;
struct Scene;

// The manifest's "units" and "conventions": what every number of the dataset means (docs/dataset-format.md), so
// a dataset explains itself without the docs.
nlohmann::json datasetUnits();
nlohmann::json datasetConventions();

// Row-major 4x4.
nlohmann::json matrixJson(const glm::dmat4& m);
// Camera-to-world pose in OpenCV camera axes (x right, y down, z forward), row-major 4x4.
nlohmann::json cameraPoseJson(const Camera& camera);
nlohmann::json colliderJson(const Collider& collider);

// Per range sensor: name, type, the sweep's start time and duration (s) and its world-from-sensor poses (sensor frame
// x forward, y left, z up) when its first and last columns fire.
nlohmann::json rangeSensorsJson(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                                double time);

// The record of `frame` (tick `frame`, time frame * sequence.time_step): rig poses and intrinsics (OpenCV pixel
// centres), wind (its clock offset by `windTimeOffset`), the colliders acting during the tick (sceneColliders;
// empty on bare ground, where none act), object poses and the sensor parameters.
nlohmann::json frameRecord(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                           const RigCameras& rig, uint32_t frame, double windTimeOffset,
                           std::span<const Collider> colliders);

} // namespace sward
