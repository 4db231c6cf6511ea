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

struct FrameBenchOptions {
    std::string scenePath;            // empty: examples/meadow.json of this source tree
    uint32_t width = 1024, height = 768;
    uint32_t samples = 4;
    uint32_t frames = 5;              // measured frames per figure (medians are reported)
    std::string device;
};

// Renders the scene and reports GPU pass times and expansion figures. Keys: pass_ms (pass -> median ms),
// plants_drawn_per_lod [near, mid, far], plants_considered, plants_total, clusters_visible, clusters_total,
// expansion_plants_per_second, frame_ms (expansion + main + resolve), static_frame_ms (main + resolve drawing
// the same quads from a pre-expanded static buffer), expansion_overhead_ratio (frame_ms / static_frame_ms),
// device, width, height, samples.
nlohmann::json benchFrame(const FrameBenchOptions& options);

} // namespace sward
