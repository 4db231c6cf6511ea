#include "range/range_benchmark.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "common/parallel_for.h"
#include "common/statistics.h"
#include "common/stopwatch.h"
#include "range/range_recorder.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

// The scene with one sensor of the preset, driving from the camera's xy towards its target at `speed` m/s.
Scene lidarScene(const LidarBenchOptions& options) {
    Scene scene =
        loadScene(options.scenePath.empty() ? std::string(SWARD_SOURCE_DIR "/examples/meadow.json") : options.scenePath,
                  {}, options.allowAssets);
    const glm::dvec2 from(scene.camera.position), to(scene.camera.lookAt);
    require(glm::distance(from, to) > 1e-3, "sward-bench lidar: the scene camera looks straight down");
    const glm::dvec2 end = from + glm::normalize(to - from) * 1000.0;
    const nlohmann::json path = {{"points", {{from.x, from.y}, {end.x, end.y}}},
                                 {"speed", std::max(options.speed, 1e-6)},
                                 {"height_above_ground", options.height}};
    nlohmann::json sensor = {{"name", "bench"}, {"preset", options.preset}, {"mount", {{"path", path}}}};
    if (options.subRays == 1)
        sensor["divergence_mrad"] = 0.0;
    else if (options.subRays > 1)
        sensor["sub_rays"] = options.subRays;
    const nlohmann::json sensors = {{"range_sensors", nlohmann::json::array({sensor})}};
    JsonReader reader(sensors, "sward-bench lidar"); // keeps a reference: `sensors` outlives it
    scene.rangeSensors = parseRangeSensors(reader);
    const RangeSensorParams& s = scene.rangeSensors[0];
    scene.sequence.timeStep = 1.0 / s.rateHz; // one frame per sweep
    scene.sequence.frames = options.sweeps + 1;
    return scene;
}

} // namespace

nlohmann::json benchLidar(const LidarBenchOptions& options) {
    const SceneResources r = buildSceneResources(lidarScene(options), true, options.threads);
    const RangeSensorParams& sensor = r.scene.rangeSensors[0];
    RangeRecorder recorder(r, options.threads);
    const Stopwatch setup;
    recorder.sweep(0, {}); // builds the BVH of every field in reach
    const double setupMs = setup.ms();
    std::vector<double> wall, cpu, points, prepare, cast;
    for (uint32_t frame = 1; frame <= options.sweeps; ++frame) {
        const Stopwatch sweep = Stopwatch::withCpuTime();
        const std::vector<RangeScan> scans = recorder.sweep(frame, {});
        wall.push_back(sweep.ms());
        cpu.push_back(sweep.cpuMs());
        points.push_back(double(scans[0].points.size()));
        prepare.push_back(recorder.timings().prepareMs), cast.push_back(recorder.timings().castMs);
    }
    const double sweepMs = median(wall), duration = 1000.0 / sensor.rateHz;
    const uint64_t beams = uint64_t(sensor.channels()) * sensor.columns();
    return {{"preset", sensor.preset},
            {"threads", resolveThreadCount(options.threads)},
            {"beams_per_sweep", beams},
            {"sub_rays", sensor.subRays},
            {"rays_per_sweep", beams * sensor.subRays},
            {"points_per_sweep", median(points)},
            {"plants_prepared", recorder.rays().plantsPrepared()},
            {"setup_ms", setupMs},
            {"sweep_ms", sweepMs},
            {"sweep_cpu_ms", median(cpu)},
            {"prepare_ms", median(prepare)},
            {"cast_ms", median(cast)},
            {"sweep_duration_ms", duration},
            {"real_time_factor", duration / sweepMs},
            {"points_per_second", median(points) / (sweepMs / 1000.0)}};
}

} // namespace sward
