// Benchmarks behind sward-bench: each returns its figures as JSON so the tool can print and save them.
// Timings are wall clock (CPU work) or GPU timestamps (GPU passes), never asserted in tests.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
    std::vector<std::string> allowAssets; // --allow-assets: more folders the scene may read assets from
    uint32_t width = 1024, height = 768;
    uint32_t samples = 4;
    uint32_t frames = 5;              // measured frames per figure (medians are reported)
    std::string device;
    std::vector<uint32_t> cutoutCorners = {4, 6, 8}; // cut-out variants measured against whole quads (4..8 each)
    bool floor = true; // also the main pass with the plants drawn by a constant-colour shader, and without plants
};

// Renders the scene and reports GPU pass times and expansion figures. Keys: pass_ms (pass -> median ms),
// whole_frame_ms and whole_frame_cpu_ms (the frame of every pass on the host, both submissions and their waits: wall
// time and the process's CPU time, every thread's, a CPU driver's included),
// plants_drawn_per_lod [near, mid, far], plants_considered, plants_total, clusters_visible, clusters_total,
// expansion_plants_per_second, frame_ms (expansion + main + resolve), static_frame_ms (main + resolve drawing
// the same quads from a pre-expanded static buffer), expansion_overhead_ratio (frame_ms / static_frame_ms),
// plant_draws (per pass "shadow", "main", "truth" and per LOD of each, "near", "mid", "far": triangles,
// triangles_after_clipping, fragment_invocations from pipeline statistics of the plant draws alone, counted in the
// untimed warm-up frame; main and truth also lanes_per_covered_pixel = invocations / covered_pixels),
// covered_pixels (pixels whose ground-truth label is a plant: vegetation, felled or cut), covered_fraction, cutout
// (per corner count of options.cutoutCorners: pass_ms, plant_draws, covered_pixels, main_lanes_ratio and
// main_ms_ratio against whole quads, pixels_differing {colour, depth, label} from the whole-quad image), floor
// (with options.floor, the same run: main_ms of the main pass with full plant shading, floor_main_ms with the plants'
// fragment shader replaced by a constant colour, without_plants_main_ms without plant draws, plant_ms and
// floor_plant_ms = each minus the pass without plants, plant_to_floor = plant_ms / floor_plant_ms), device, width,
// height, samples.
nlohmann::json benchFrame(const FrameBenchOptions& options);

struct CollideBenchOptions {
    std::vector<uint32_t> fields = {10, 100, 400}; // cases: colliders on the first N fields of the tile (1..400)
    uint32_t ticks = 30;   // measured ticks per case, after the warm-up (medians are reported)
    uint32_t warmup = 5;   // ticks per case before measuring
    uint32_t threads = 0;  // collision threads, 0 = all cores
    float density = 16.0f; // grass plants per m^2 (flat 500 x 500 m tile: 400 fields of 25 clusters)
    float radius = 0.5f;   // collider sphere radius, metres
    double tickRate = 0.0; // > 0: ticks start 1 / tickRate s apart, as in a real-time loop; 0: back to back
    std::string device;
    bool gpu = true;       // false: CPU collision only, no Vulkan device (GPU and upload figures are 0)
};

// The paper's interaction worst case on a synthetic flat tile (no scene file): one pushing sphere per 5 x 5 m
// cluster of N fields, circling slowly (its contacts change every tick), through the CPU collision pass and the
// GPU contact + recovery passes. Keys: results (per case: fields, colliders, contacts, active_fields,
// cpu_collision_ms (wall clock), cpu_collision_cpu_time_ms (process CPU time, all collision threads together),
// upload_bytes, upload_ms, gpu_recovery_ms, gpu_recovery_ms_per_field, total_ms; medians per tick),
// idle_colliders (10,000 spheres 50 m above the grass), idle_colliders_ms (their collision + upload + GPU cost per
// tick), zero_active_recovery_dispatches (GPU dispatches over ticks with no active field: must be 0),
// zero_active_ticks, plants, density, radius, tick_rate, threads, ticks, device.
nlohmann::json benchCollide(const CollideBenchOptions& options);
// The per-case figures of benchCollide's result as an aligned text table.
std::string collideTable(const nlohmann::json& result);

struct WorldBenchOptions {
    std::string scenePath;                // empty: examples/world.json of this source tree; needs a "world"
    std::vector<std::string> allowAssets; // --allow-assets
    float densityMultiplier = 0.0f;       // > 0: replaces vegetation.density_multiplier (faster runs)
    uint32_t threads = 0;                 // per tile generation, 0 = all cores
    uint32_t tiles = 4;                   // tiles generated one by one for the generation figures
    std::vector<uint32_t> resident = {1, 4, 9, 16, 25}; // resident-tile counts of the memory figures
    bool noGpu = false;                   // --no-gpu: CPU figures only
    std::string device;                   // device name filter (GPU figures)
    uint32_t width = 640, height = 360;   // frame size of the GPU figures
    uint32_t frames = 3;                  // timed frames per resident count (after one warm-up)
};

// The CPU side of a world of many tiles (scene/world_tiles.h). Keys: generation (per tile: ms wall and CPU (process,
// all threads), plants, plants_per_second; medians), tile_bytes (resident bytes of one tile), predicted_tile_bytes
// (the budget's upper bound), memory (per world size "4x4" / "16x16": per resident count n: resident_tiles,
// resident_bytes, bytes_per_tile, ratio_to_n_times_one (resident_bytes / (n * bytes of one tile)), wait_ms),
// same_radius (one camera at the scene's load radius in a 4x4 and a 16x16 world: resident tiles and bytes of each),
// threads, density_multiplier, tile_size, scene; gpu (null with noGpu): device, resolution, frames, view_distance,
// rows per resident count 1, 4, 9, 16 with the camera seeing one tile: upload_ms_per_tile, frame_ms (wall, median,
// frame + readback), frame_cpu_ms (process CPU), same_image_as_one_tile (bitwise).
nlohmann::json benchWorld(const WorldBenchOptions& options);
// The memory figures of benchWorld's result as an aligned text table.
std::string worldTable(const nlohmann::json& result);

struct DatasetBenchOptions {
    std::string scenePath;                 // empty: examples/rover-track.json of this source tree
    std::vector<std::string> allowAssets;  // --allow-assets
    std::optional<std::string> resolution; // "WxH"; default: the scene's
    std::optional<uint32_t> samples;       // 1 or 4; default: the scene's
    uint32_t frames = 6;                   // frames 0 .. frames - 1; the first is the warm-up (at least 2)
    std::string device;
};

// sward-render's whole job (render_job.h: render, read back, write every file) into a temporary folder, removed
// afterwards. Keys: frames_per_second and seconds_per_frame over the frames after the first (the first frame's files
// on disk to the last's), cpu_seconds_per_frame (process CPU time over the same span: every thread, the driver's
// too), cpu_utilisation (CPU seconds per wall second), render_seconds, write_seconds and wait_seconds (medians over
// those frames: rendering and reading back, encoding and writing the files on the writer's thread beside the next
// render, waiting for the writer), setup_seconds (the run's start to the first frame), first_frame_seconds,
// manifest_seconds (after the last frame: hashing every file, writing the manifest), bytes_per_frame (the frames'
// files), frames, scene, resolution, samples, device.
nlohmann::json benchDataset(const DatasetBenchOptions& options);

} // namespace sward
