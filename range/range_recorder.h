// The range sensors of a sequence: one RayScene for the whole run and, per frame, the plants' state after the frame's
// tick, the objects' poses, each sensor's sweep and its files. Used by the render job (sward-render) and the
// benchmarks, so a dataset's range files and a benchmark's sweeps are the same computation.
#pragma once

#include "dataset/dataset_writer.h"
#include "range/range_sweep.h"
#include "scene/scene_resources.h"

#include <memory>
#include <span>
#include <vector>

namespace sward {

class RangeRecorder {
public:
    // `r` must outlive the recorder, with its tile (a one-tile scene; null without vegetation) and atlas still
    // present: build it before createSceneGpu releases the CPU copies (it keeps the tile of a scene with range sensors).
    // A world (r.world): each sweep casts against the resident tiles within the sensors' reach, read as they are then
    // (their CPU copies: a world simulation's tiles read back first, rangeFrameState); every tile within
    // 'max_range_m' + 2 m (plants lean out of their tile) of any origin of a sweep must be resident, which the sweep's
    // start as an interest point (rangeSensorStarts) within 'world.load_radius' guarantees.
    explicit RangeRecorder(const SceneResources& r, uint32_t threads = 0);
    ~RangeRecorder();

    bool active() const { return rays_ != nullptr; } // the scene has range sensors

    // What the frame shows besides the scene itself: the plants' state `dynamics` (the tile's dynamic records after
    // the frame's tick, tile order; empty: at rest), the ground's rut patches, and the wind's clock offset
    // (sward-render --time).
    struct FrameState {
        std::span<const gpu::PlantDynamic> dynamics;
        // Shared and never changed once made (a new set of ruts is a new vector): the scene rebuilds its rut patches
        // only when this pointer changes.
        std::shared_ptr<const std::vector<GroundPatch>> patches;
        double windTimeOffset = 0.0;
    };
    // Every sensor's sweep of frame `frame` (starting at the frame's time). A world: throws sward::Error naming
    // 'world.load_radius' when a sensor's reach (its range, 2 m and how far it moves in the sweep) exceeds it.
    std::vector<RangeScan> sweep(uint32_t frame, const FrameState& state);
    // The same, with each scan's files written through `dataset`.
    void record(DatasetWriter& dataset, uint32_t frame, const FrameState& state);
    // The files of scans sweep() made for frame `frame`.
    void write(DatasetWriter& dataset, uint32_t frame, const std::vector<RangeScan>& scans) const;

    const RayScene& rays() const { return *rays_; }
    // Wall time of the latest sweep(): preparing the scene (plants, objects) and casting, milliseconds.
    struct Timings {
        double prepareMs = 0.0, castMs = 0.0;
    };
    Timings timings() const { return timings_; }

private:
    std::vector<RangeScan> sweepWorld(uint32_t frame, const FrameState& state);

    const SceneResources& r_;
    uint32_t threads_;
    std::unique_ptr<RayScene> rays_;
    std::shared_ptr<const std::vector<GroundPatch>> patches_; // those the RayScene holds
    Timings timings_;
};

} // namespace sward
