#include "range/range_recorder.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "common/stopwatch.h"
#include "range/range_files.h"
#include "scene/world_objects.h"

#include <algorithm>
#include <set>
#include <utility>

namespace sward {

RangeRecorder::RangeRecorder(const SceneResources& r, uint32_t threads) : r_(r), threads_(threads) {
    if (r.scene.rangeSensors.empty()) return;
    if (r.world) { // the tiles come with each sweep
        require(!r.withVegetation() || r.atlas, "range sensors: the vegetation was released before them");
        rays_ = std::make_unique<RayScene>(r.atlas ? *r.atlas : Atlas{}, r.scene.vegetation, r.scene.world.tilesX,
                                           r.scene.lod.nearBlades);
        return;
    }
    const VegetationTile* tile = r.withVegetation() && r.tile ? &*r.tile : nullptr;
    require(!r.withVegetation() || (tile && r.atlas), "range sensors: the vegetation was released before them");
    rays_ = std::make_unique<RayScene>(r.terrain, r.atlas ? *r.atlas : Atlas{}, r.scene.vegetation, tile,
                                       r.scene.lod.nearBlades);
}

RangeRecorder::~RangeRecorder() = default;

std::vector<RangeScan> RangeRecorder::sweep(uint32_t frame, const FrameState& state) {
    require(active(), "the scene has no range sensors");
    if (r_.world) return sweepWorld(frame, state);
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

// A world: each sensor stands on the world's lattice ground around its sweep (latticeGround: bitwise the tiles'
// heights, as the cameras stand), and the rays meet the tiles within its reach of where its sweep starts, ascending
// (y, x): the scene, and so every point, is a function of the scene, the frame and the plants' state, never of which
// other tiles happen to be resident.
std::vector<RangeScan> RangeRecorder::sweepWorld(uint32_t frame, const FrameState& state) {
    const Scene& scene = r_.scene;
    const double time = double(frame) * scene.sequence.timeStep;
    require(state.dynamics.empty(), "range sensors: a world's tiles hold their plants' state");
    std::vector<Ground> grounds;
    std::vector<glm::dvec2> starts;
    std::vector<double> reaches;
    std::set<std::pair<int32_t, int32_t>> wanted; // (y, x)
    for (const RangeSensorParams& sensor : scene.rangeSensors) {
        Ground ground = sweepGround(scene, r_.models, sensor, time);
        const std::vector<glm::dvec2> origins = sweepOrigins(scene, r_.models, sensor, ground, time);
        double motion = 0.0;
        for (const glm::dvec2& o : origins) motion = std::max(motion, glm::distance(o, origins[0]));
        // A plant stands in its tile but leans out of it, as out of its field (range/plant_fields.cpp).
        const double reach = sensor.maxRange + motion + kPlantLean;
        require(reach <= scene.world.loadRadius,
                scene.source + ": range sensor '" + sensor.name + "' reaches " + formatNumber(reach) +
                    " m from where its sweep of frame " + std::to_string(frame) + " starts (its 'range', " +
                    formatNumber(kPlantLean) + " m and its motion in the sweep), beyond 'world.load_radius' (" +
                    formatNumber(scene.world.loadRadius) + " m): its rays would meet tiles that need not be resident");
        for (TileCoord coord : tilesWithin(scene, origins[0], reach)) wanted.insert({coord.y, coord.x});
        grounds.push_back(std::move(ground));
        starts.push_back(origins[0]), reaches.push_back(reach);
    }
    std::vector<RayTile> tiles;
    for (const auto& [y, x] : wanted) {
        const WorldTile* tile = r_.world->find(TileCoord{x, y});
        require(tile != nullptr, "range sensors: tile (" + std::to_string(x) + ", " + std::to_string(y) +
                                     ") is within reach but not resident (its sweep's start was no interest point)");
        tiles.push_back({tile->coord, &tile->ground, tile->vegetation.fields.empty() ? nullptr : &tile->vegetation});
    }
    const Stopwatch preparing;
    rays_->setTiles(tiles);
    // The plants of every field within reach of the sensors: around their mean start, out to the farthest reach.
    glm::dvec2 centre(0.0);
    for (const glm::dvec2& s : starts) centre += s / double(starts.size());
    double reach = 0.0;
    for (size_t k = 0; k < starts.size(); ++k) reach = std::max(reach, glm::distance(centre, starts[k]) + reaches[k]);
    rays_->setPlants(scene.wind, time + state.windTimeOffset, {}, centre, reach, threads_);
    // Each object on its own lattice ground, as it is drawn (scene/world_objects.h).
    std::vector<PosedTriangles> objects;
    for (size_t k = 0; k < scene.objects.size() && k < r_.models.size(); ++k)
        objects.push_back(
            posedObject(scene, k, r_.models[k], objectGround(scene, scene.objects[k], r_.models[k], time), time));
    rays_->setObjects(objects);
    if (state.patches != patches_) { // the world's ruts: its tracks are world-wide, never evicted
        rays_->setGroundPatches(state.patches ? *state.patches : std::vector<GroundPatch>{});
        patches_ = state.patches;
    }
    const double prepareMs = preparing.ms();
    const Stopwatch casting;
    std::vector<RangeScan> scans;
    for (uint32_t k = 0; k < scene.rangeSensors.size(); ++k)
        scans.push_back(sweepSensor(*rays_, {scene, grounds[k], r_.models}, k, frame, time, threads_));
    timings_ = {prepareMs, casting.ms()};
    return scans;
}

void RangeRecorder::record(DatasetWriter& dataset, uint32_t frame, const FrameState& state) {
    write(dataset, frame, sweep(frame, state));
}

void RangeRecorder::write(DatasetWriter& dataset, uint32_t frame, const std::vector<RangeScan>& scans) const {
    require(scans.size() == r_.scene.rangeSensors.size(), "range sensors: a scan per sensor");
    for (size_t k = 0; k < scans.size(); ++k) writeRangeFiles(dataset, r_.scene.rangeSensors[k], scans[k], frame);
}

} // namespace sward
