// Benchmarks behind sward-bench: each returns its figures as JSON so the tool can print and save them.
// Timings are wall clock (CPU work) or GPU timestamps (GPU passes), never asserted in tests.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace sward {

struct GenerateBenchOptions {
    float density = 16.0f;  // grass plants per m^2 over the whole tile (uniform grass map)
    float tileSize = 500.0f;
    uint32_t threads = 0;   // 0 = all cores
    uint32_t repeats = 3;   // generation runs; the median is reported
    std::string device;     // for the upload
    bool upload = true;
};

// Generates one full tile and uploads it. Keys: plants, seconds, plants_per_second, static_bytes_per_plant,
// dynamic_bytes_per_plant, cluster_bytes_per_plant, upload_seconds, total_seconds, threads, density, tile_size,
// device, runs_seconds.
nlohmann::json benchGenerate(const GenerateBenchOptions& options);

} // namespace sward
