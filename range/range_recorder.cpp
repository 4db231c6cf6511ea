#include "range/range_recorder.h"

#include "common/error.h"
#include "common/stopwatch.h"
#include "range/range_files.h"

#include <algorithm>

namespace sward {

RangeRecorder::RangeRecorder(const SceneResources& r, uint32_t threads) : r_(r), threads_(threads) {
    if (r.scene.rangeSensors.empty()) return;
    require(!r.world, r.scene.source + ": 'range_sensors' need a scene of one tile (not a 'world')");
    const VegetationTile* tile = r.withVegetation() && r.tile ? &*r.tile : nullptr;
    require(!r.withVegetation() || (tile && r.atlas), "range sensors: the vegetation was released before them");
    rays_ = std::make_unique<RayScene>(r.terrain, r.atlas ? *r.atlas : Atlas{}, r.scene.vegetation, tile,
                                       r.scene.lod.nearBlades);
}

RangeRecorder::~RangeRecorder() = default;

std::vector<RangeScan> RangeRecorder::sweep(uint32_t frame, const FrameState& state) {
    require(active(), "the scene has no range sensors");
    const Scene& scene = r_.scene;
    const double time = double(frame) * scene.sequence.timeStep;
    // The plants every sensor can reach during its sweep: within its range of where it is at the start, plus how far
    // it moves until the end.
    glm::dvec2 centre(0.0);
    std::vector<glm::dvec2> starts;
    for (const RangeSensorParams& sensor : scene.rangeSensors) {
        starts.push_back(glm::dvec2(rangeSensorPose(scene, sensor, r_.terrain, r_.models, time)[3]));
        centre += starts.back() / double(scene.rangeSensors.size());
    }
    double reach = 0.0;
    for (size_t k = 0; k < starts.size(); ++k) {
        const RangeSensorParams& sensor = scene.rangeSensors[k];
        const glm::dvec2 end(
            rangeSensorPose(scene, sensor, r_.terrain, r_.models, time + columnTime(sensor, sensor.columns() - 1))[3]);
        reach = std::max(reach, glm::distance(centre, starts[k]) + glm::distance(starts[k], end) + sensor.maxRange);
    }
    const Stopwatch preparing;
    rays_->setPlants(scene.wind, time + state.windTimeOffset, state.dynamics, centre, reach, threads_);
    rays_->setObjects(posedObjects({scene, r_.terrain, r_.models}, time));
    if (state.patches != patches_) {
        rays_->setGroundPatches(state.patches ? *state.patches : std::vector<GroundPatch>{});
        patches_ = state.patches;
    }
    const double prepareMs = preparing.ms();
    const Stopwatch casting;
    std::vector<RangeScan> scans;
    for (uint32_t k = 0; k < scene.rangeSensors.size(); ++k)
        scans.push_back(sweepSensor(*rays_, {scene, r_.terrain, r_.models}, k, frame, time, threads_));
    timings_ = {prepareMs, casting.ms()};
    return scans;
}

void RangeRecorder::record(DatasetWriter& dataset, uint32_t frame, const FrameState& state) {
    const std::vector<RangeScan> scans = sweep(frame, state);
    for (size_t k = 0; k < scans.size(); ++k) writeRangeFiles(dataset, r_.scene.rangeSensors[k], scans[k], frame);
}

} // namespace sward
