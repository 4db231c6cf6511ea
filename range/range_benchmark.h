// sward-bench lidar: range sensors against real time (docs/benchmarks.md).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

struct LidarBenchOptions {
    std::string scenePath; // default: examples/meadow.json of this source tree
    std::vector<std::string> allowAssets;
    std::string preset = "VLP-16"; // the sensor (scene/range_sensors.h presets)
    double height = 1.0;           // metres above the ground, at the scene camera's xy, facing its view
    double speed = 1.0;            // metres per second the sensor drives towards the camera's target
    uint32_t subRays = 0;          // rays per beam (1, 7 or 19; 0: the preset's)
    uint32_t sweeps = 10;          // measured sweeps (frames at the sensor's rate)
    uint32_t threads = 0;          // 0 = all cores
};

// Loads the scene with a sensor of `preset` added (driving at `speed` from the scene camera's xy), sweeps once to build
// the plants' BVHs (reported as setup), then `sweeps` times. Keys: preset, beams_per_sweep, rays_per_sweep (sub-rays
// included), points_per_sweep (median), plants_prepared, setup_ms, sweep_ms / sweep_cpu_ms (medians, wall and process
// CPU time), plants_ms and cast_ms (median split), sweep_duration_ms (the sensor's own), real_time_factor (sweep
// duration / sweep wall time; >= 1: real time), points_per_second, threads.
nlohmann::json benchLidar(const LidarBenchOptions& options);

} // namespace sward
