// Range sensors in a world of several tiles (issue 51): a LiDAR riding beside a rover across tile borders casts
// against the resident tiles within its reach. Its points agree with the camera's truth depth where both see the same
// surface (the one-tile test's method, render/range_sensor_test.cpp), on the ground and the plants of two and more
// tiles, pressed plants included; and they are bitwise the same whether the tiles stream around the sensor or the
// whole world stays resident.
#include "gpu_test.h"

#include "range/range_recorder.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/rover_model.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <utility>

using namespace sward;
using sward::test::GpuTest;

namespace {

// The agreement needs the one-tile test's resolution: at 160 x 120 a plant 3 m away spans few pixels, and a 2 x 2
// neighbourhood often straddles two of its quads (median 6e-4 there, on one tile as in a world).
constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr double kTile = 20.0;

// 4 x 4 tiles of 20 m. The camera and the LiDAR (the same path, 2.2 m above the ground) drive east along y = 17,
// 3 m south of the border y = 20, at 4 m/s, behind a rover that presses the grass along y = 21 (on the border).
// Every plant within the LiDAR's 15 m is drawn in the near LOD (the range sensors' LOD), out to lod.near 16 m.
// `loadRadius` 18 m streams (evict 22 m: tile column 0 goes by frame 140); 400 m keeps every tile resident.
nlohmann::json lidarWorldJson(double loadRadius) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 11,
        "terrain": {"size": 20, "spacing": 1, "amplitude": 2, "feature_size": 50, "octaves": 3},
        "vegetation": {"tile_size": 20, "field_size": 10},
        "world": {"tiles": [4, 4], "view_distance": 18, "memory_budget_mib": 256},
        "camera": {"path": {"points": [[2, 17], [78, 17]], "speed": 4, "height_above_ground": 2.2},
                   "look_ahead": 8, "look_at_height_above_ground": 0, "fov_y_deg": 70, "baseline": 0},
        "vehicles": [{"path": {"points": [[14, 21], [78, 21]], "speed": 4}, "weight": 2,
                      "wheel_radius": 0.4, "wheel_width": 1.0, "track_width": 1.6, "wheel_base": 1.2}],
        "range_sensors": [{"name": "lidar", "preset": "VLP-16", "divergence_mrad": 0, "range_noise_m": 0,
                           "angle_step_deg": 0.2, "angle_range_deg": [-50, 50], "range": [0.5, 15],
                           "mount": {"path": {"points": [[2, 17], [78, 17]], "speed": 4,
                                              "height_above_ground": 2.2}}}],
        "render": {"shadow_map_size": 256, "shadow_distance": 18},
        "lod": {"near": 16, "mid": 16.5, "far": 17, "band": 2},
        "sequence": {"frames": 200, "time_step": 0.1}
    })");
    std::vector<double> elevations; // every degree from 45 down to 5 below the horizon
    for (int e = -45; e <= -5; ++e) elevations.push_back(e);
    json["range_sensors"][0]["elevations_deg"] = elevations;
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 4.0;
    return json;
}

// The same world with the LiDAR 0.3 m above the camera mount of a rover (an object, its chassis pressing the grass)
// that drives where the vehicle did; the rover's model is written into `dir`.
nlohmann::json roverLidarWorldJson(double loadRadius, const std::string& dir) {
    nlohmann::json json = lidarWorldJson(loadRadius);
    saveRoverGltf(dir + "/rover.gltf");
    json.erase("vehicles");
    json["objects"] = {{{"name", "rover"},
                        {"model", "rover.gltf"},
                        {"scale", 2},
                        {"path", {{"points", {{14, 21}, {78, 21}}}, {"speed", 4}}},
                        {"colliders",
                         {{{"node", "chassis"},
                           {"shape", "box"},
                           {"half_extents", {0.4, 0.55, 0.3}},
                           {"offset", {0, 0, -0.15}},
                           {"force", 2}}}}}};
    json["range_sensors"][0]["mount"] = {{"object", "rover"}, {"node", "camera_mount"}, {"offset", {0, 0, 0.3}}};
    json["range_sensors"][0].erase("angle_range_deg"); // a full turn: the track behind the rover too
    return json;
}

Scene lidarWorld(double loadRadius, const std::string& roverDir = "") {
    if (!roverDir.empty()) return parseScene(roverLidarWorldJson(loadRadius, roverDir), roverDir + "/scene.json");
    return parseScene(lidarWorldJson(loadRadius), "lidar world");
}

struct LidarRun {
    std::vector<FrameImages> frames;
    std::vector<Camera> cameras; // left
    std::vector<RangeScan> scans;
    WorldTileStats stats;
    uint32_t mostResident = 0;
};

// Renders `frames` (ascending) at width x height and sweeps the LiDAR after each, as sward-render does.
// `roverDir`: the LiDAR on the rover (roverLidarWorldJson).
LidarRun drive(Context& ctx, double loadRadius, const std::vector<uint32_t>& frames, uint32_t width = kWidth,
               uint32_t height = kHeight, const std::string& roverDir = "") {
    SceneResources r = buildSceneResources(lidarWorld(loadRadius, roverDir), true, 2);
    RangeRecorder range(r, 2);
    RutPatchCache ruts;
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_TRUE(gpu.worldSimulation != nullptr);

    OffscreenFrame target(ctx, width, height, 1);
    LidarRun run;
    for (uint32_t frame : frames) {
        RigCameras cameras;
        run.frames.push_back(renderSequenceFrame(gpu, target, r, width, height, frame, 0.0, std::nullopt, cameras));
        run.cameras.push_back(cameras.left);
        const RangeFrameState state = rangeFrameState(gpu, r, ruts);
        run.scans.push_back(std::move(range.sweep(frame, state.view(0.0)).at(0)));
        std::printf("frame %u: %zu points, %u tiles resident, sweep prepared in %.1f ms, cast in %.1f ms\n", frame,
                    run.scans.back().points.size(), r.world->residentCount(), range.timings().prepareMs,
                    range.timings().castMs);
        run.mostResident = std::max(run.mostResident, r.world->residentCount());
    }
    run.stats = r.world->stats();
    return run;
}

std::pair<int, int> tileOf(const glm::dvec3& p) {
    return {int(std::floor(p.x / kTile)), int(std::floor(p.y / kTile))};
}

bool isPlant(uint32_t semantic) {
    return semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject;
}

double median(std::vector<double> v) {
    if (v.empty()) return 1.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

} // namespace

// Frame 95: the camera and the LiDAR at x = 40, where four tiles meet 3 m to the north; the rover 12 m ahead has
// pressed the grass along the border y = 20 behind it. Each LiDAR point whose four surrounding pixels show its class,
// instance (and, for a plant, the tile under it) lies at the camera's truth depth there.
TEST_F(GpuTest, WorldLidarPointsAgreeWithTheCameraDepthAcrossTileBorders) {
    const LidarRun run = drive(*ctx, 18.0, {85});
    const FrameImages& im = run.frames[0];
    const Camera& camera = run.cameras[0];
    ASSERT_EQ(im.tiles.size(), im.labels.size());
    std::vector<double> relative, plantRelative;
    std::set<std::pair<int, int>> tiles;
    std::set<uint32_t> plantTiles; // RangePoint::tile
    uint32_t plants = 0, felled = 0, ground = 0;
    for (const RangePoint& p : run.scans[0].points) {
        const glm::dvec3 pixel = camera.project(p.world);
        if (pixel.z <= 0.1) continue;
        const int x0 = int(std::floor(pixel.x - 0.5)), y0 = int(std::floor(pixel.y - 0.5)); // pixel centres
        if (x0 < 0 || y0 < 0 || x0 + 1 >= int(kWidth) || y0 + 1 >= int(kHeight)) continue;
        const uint32_t semantic = p.label >> gpu::kInstanceBits, instance = p.label & ((1u << gpu::kInstanceBits) - 1);
        const auto [tx, ty] = tileOf(p.world);
        bool same = true;
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const size_t i = size_t(y0 + dy) * kWidth + size_t(x0 + dx);
                const uint32_t s = im.labels[i] >> gpu::kInstanceBits;
                const bool sameClass = s == semantic || (semantic == gpu::kSemanticGround &&
                                                         (s == gpu::kSemanticTurf || s == gpu::kSemanticTrack));
                same = same && sameClass && (im.labels[i] & ((1u << gpu::kInstanceBits) - 1)) == instance &&
                       im.tiles[i] == p.tile;
            }
        if (!same) continue;
        // Inverse depth is linear across the image of a plane: interpolate it bilinearly.
        const double fx = pixel.x - 0.5 - x0, fy = pixel.y - 0.5 - y0;
        auto inv = [&](int x, int y) { return 1.0 / double(im.depth[size_t(y) * kWidth + size_t(x)]); };
        const double inverse = (inv(x0, y0) * (1 - fx) + inv(x0 + 1, y0) * fx) * (1 - fy) +
                               (inv(x0, y0 + 1) * (1 - fx) + inv(x0 + 1, y0 + 1) * fx) * fy;
        relative.push_back(std::abs(pixel.z * inverse - 1.0));
        tiles.insert({tx, ty});
        if (isPlant(semantic)) plantRelative.push_back(relative.back()), plantTiles.insert(p.tile);
        plants += isPlant(semantic);
        felled += semantic == gpu::kSemanticFelled;
        ground += semantic == gpu::kSemanticGround;
    }
    std::printf("%zu LiDAR points on surfaces the camera sees (%u plant, %u felled, %u ground) in %zu tiles (plants in "
                "%zu): median relative depth difference %.3g (plants %.3g)\n",
                relative.size(), plants, felled, ground, tiles.size(), plantTiles.size(), median(relative),
                median(plantRelative));
    ASSERT_GT(relative.size(), 500u);
    EXPECT_LT(median(relative), 1e-4);
    EXPECT_LT(median(plantRelative), 1e-4);
    EXPECT_GT(plants, 100u);
    EXPECT_GT(ground, 100u);
    EXPECT_GT(felled, 0u) << "the rover's pressed plants: the world simulation's records are read back";
    EXPECT_GE(tiles.size(), 3u) << "the points lie on several tiles";
    EXPECT_GE(plantTiles.size(), 2u);
}

// The same drive with tiles streaming around the camera, the LiDAR and the rover (load_radius 18 m: tiles come and
// go) and with the whole world resident: every point of every sweep is bitwise the same.
TEST_F(GpuTest, WorldLidarPointsAreBitwiseTheSameStreamedOrResident) {
    const std::vector<uint32_t> frames{85, 140};
    const LidarRun streamed = drive(*ctx, 18.0, frames, 64, 48);
    const LidarRun resident = drive(*ctx, 400.0, frames, 64, 48);
    EXPECT_GT(streamed.stats.evicted, 0u) << "the drive must leave tiles behind";
    EXPECT_LT(streamed.mostResident, 16u);
    EXPECT_EQ(resident.stats.evicted, 0u);
    EXPECT_EQ(resident.mostResident, 16u);
    for (size_t f = 0; f < frames.size(); ++f) {
        const RangeScan& a = streamed.scans[f];
        const RangeScan& b = resident.scans[f];
        EXPECT_GT(a.points.size(), 10000u) << "frame " << frames[f];
        ASSERT_EQ(a.points.size(), b.points.size()) << "frame " << frames[f];
        EXPECT_EQ(a.ranges, b.ranges) << "frame " << frames[f];
        std::set<std::pair<int, int>> tiles;
        uint64_t different = 0;
        for (size_t i = 0; i < a.points.size(); ++i) {
            const RangePoint &p = a.points[i], &q = b.points[i];
            different += p.world != q.world || p.sensor != q.sensor || p.label != q.label || p.tile != q.tile ||
                         p.intensity != q.intensity || p.ring != q.ring || p.column != q.column;
            tiles.insert(tileOf(p.world));
        }
        EXPECT_EQ(different, 0u) << "frame " << frames[f];
        EXPECT_GE(tiles.size(), 3u) << "frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].depth, resident.frames[f].depth) << "frame " << frames[f];
    }
}

// A LiDAR on a rover (an object on its own lattice ground) sweeps the same points streamed as resident; it sees the
// ground and plants of several tiles and the grass the rover's chassis pressed.
TEST_F(GpuTest, WorldLidarOnARoverIsBitwiseTheSameStreamedOrResident) {
    const std::string dir = sward::test::tempDir("world-rover-lidar");
    const std::vector<uint32_t> frames{85, 140};
    const LidarRun streamed = drive(*ctx, 18.0, frames, 64, 48, dir);
    const LidarRun resident = drive(*ctx, 400.0, frames, 64, 48, dir);
    EXPECT_GT(streamed.stats.evicted, 0u);
    EXPECT_EQ(resident.stats.evicted, 0u);
    uint64_t felled = 0, rover = 0;
    for (size_t f = 0; f < frames.size(); ++f) {
        const RangeScan& a = streamed.scans[f];
        const RangeScan& b = resident.scans[f];
        EXPECT_GT(a.points.size(), 5000u) << "frame " << frames[f];
        ASSERT_EQ(a.points.size(), b.points.size()) << "frame " << frames[f];
        EXPECT_EQ(a.ranges, b.ranges) << "frame " << frames[f];
        EXPECT_EQ(a.startPose, b.startPose) << "frame " << frames[f];
        std::set<std::pair<int, int>> tiles;
        uint64_t different = 0;
        for (size_t i = 0; i < a.points.size(); ++i) {
            const RangePoint &p = a.points[i], &q = b.points[i];
            different += p.world != q.world || p.label != q.label || p.tile != q.tile || p.intensity != q.intensity;
            tiles.insert(tileOf(p.world));
            felled += (p.label >> gpu::kInstanceBits) == gpu::kSemanticFelled;
            rover += (p.label >> gpu::kInstanceBits) == gpu::kSemanticObject;
        }
        EXPECT_EQ(different, 0u) << "frame " << frames[f];
        EXPECT_GE(tiles.size(), 2u) << "frame " << frames[f];
    }
    std::printf("rover LiDAR: %zu and %zu points, %llu felled, %llu on the rover\n", streamed.scans[0].points.size(),
                streamed.scans[1].points.size(), (unsigned long long)felled, (unsigned long long)rover);
    EXPECT_GT(felled, 0u) << "the rover's chassis presses the grass it drives over";
    EXPECT_GT(rover, 0u) << "the objects are in the ray scene (the LiDAR sees the rover it rides)";
}

// sward-render casts a world's sweeps before the next frame may evict their tiles: the streamed and the resident
// world's datasets are the same file for file (range files, frames.jsonl with the LiDAR's poses on the world's ground,
// images), across the border x = 20 m.
TEST_F(GpuTest, WorldLidarDatasetsAreTheSameStreamedOrResident) {
    std::map<double, std::string> out;
    for (double loadRadius : {18.0, 400.0}) {
        const std::string dir = sward::test::tempDir("world-lidar-" + std::to_string(int(loadRadius)));
        std::ofstream(dir + "/scene.json") << lidarWorldJson(loadRadius).dump(1);
        std::string err;
        ASSERT_EQ(sward::test::runSwardRender(
                      dir + "/scene.json --out " + dir + "/out --frames 40:42 --resolution 64x48", err),
                  0)
            << err;
        out[loadRadius] = dir + "/out";
    }
    EXPECT_GE(sward::test::expectSameRunFiles(out[18.0], out[400.0]), 12u);
    // A world's points name their plants' tiles (instance ids count within a tile).
    EXPECT_NE(sward::test::readFile(out[18.0] + "/range/lidar/000041.ply")
                  .find("property uint instance\nproperty uint tile\n"),
              std::string::npos);
    // The LiDAR stands 2.2 m above the ground it is drawn on, as the camera on the same path does.
    std::istringstream lines(sward::test::readFile(out[18.0] + "/frames.jsonl"));
    uint32_t records = 0;
    for (std::string line; std::getline(lines, line); ++records) {
        const nlohmann::json record = nlohmann::json::parse(line);
        EXPECT_NEAR(double(record["range_sensors"][0]["start_pose"][2][3]), double(record["left_pose"][2][3]), 1e-6)
            << line;
    }
    EXPECT_EQ(records, 200u); // the whole sequence
}
