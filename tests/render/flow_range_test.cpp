// render.flow together with range_sensors (issue 51, part I). With flow a frame runs its next tick before its truth
// passes, so the plants' live records and the ruts are one tick ahead when the frame returns; the range sensors' sweep
// of frame f must still see tick f, as the cameras drew it (render/sequence_frame.h, rangeFlowFrameState). Checked
// through sward-render datasets: a rover felling grass and pressing ruts, a LiDAR seeing both, on one tile and in a
// world of small tiles, whose range files are bitwise the same with flow on or off (and streamed or resident).
#include "gpu_test.h"

#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

using sward::test::expectSameRunFiles;
using sward::test::readFile;
using sward::test::tempDir;

namespace {

std::string writeScene(const nlohmann::json& scene, const std::string& name) {
    const std::string path = tempDir("flow-range-scene-" + name) + "/scene.json";
    std::ofstream(path) << scene.dump(2);
    return path;
}

// The dataset's `frames` (a --frames range) of `scene` at 64x48, rendered into a new folder `name`.
std::string renderDataset(const nlohmann::json& scene, const std::string& name, const std::string& frames) {
    const std::string out = tempDir("flow-range-" + name);
    std::string err;
    EXPECT_EQ(sward::test::runSwardRender(
                  writeScene(scene, name) + " --out " + out + " --frames " + frames + " --resolution 64x48", err),
              0)
        << err;
    return out;
}

// How many points of a range PLY hit each semantic class (its header's "class" property).
std::map<uint32_t, uint32_t> classCounts(const std::string& path) {
    const std::string bytes = readFile(path);
    const size_t end = bytes.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    const std::map<std::string, size_t> sizes = {{"float", 4}, {"double", 8}, {"uchar", 1}, {"ushort", 2}, {"uint", 4}};
    std::istringstream header(bytes.substr(0, end));
    size_t stride = 0, classOffset = 0;
    for (std::string line; std::getline(header, line);) {
        std::istringstream words(line);
        std::string a, type, name;
        words >> a >> type >> name;
        if (a != "property") continue;
        if (name == "class") classOffset = stride;
        stride += sizes.at(type);
    }
    std::map<uint32_t, uint32_t> counts;
    for (size_t at = end + 11; at + stride <= bytes.size(); at += stride) ++counts[uint8_t(bytes[at + classOffset])];
    return counts;
}

// The range files of frames [first, end) of datasets `a` and `b`, bytewise; each frame's LiDAR sees felled grass and
// ruts (what the rover changed at every tick: a sweep one tick late would differ there).
void expectSameRangeFiles(const std::string& a, const std::string& b, uint32_t first, uint32_t end) {
    for (uint32_t frame = first; frame < end; ++frame) {
        char name[64];
        for (const char* extension : {".ply", ".bin", ".label"}) {
            std::snprintf(name, sizeof(name), "/range/lidar/%06u%s", frame, extension);
            const std::string bytes = readFile(a + name);
            EXPECT_FALSE(bytes.empty()) << name;
            EXPECT_TRUE(bytes == readFile(b + name)) << name; // binary: not printed
        }
        std::snprintf(name, sizeof(name), "/range/lidar/%06u.ply", frame);
        std::map<uint32_t, uint32_t> counts = classCounts(a + name);
        std::printf("frame %u: %u LiDAR points on felled grass, %u on ruts, %u on standing grass, %u on the ground\n",
                    frame, counts[sward::gpu::kSemanticFelled], counts[sward::gpu::kSemanticTrack],
                    counts[sward::gpu::kSemanticVegetation + 1], counts[sward::gpu::kSemanticGround]);
        EXPECT_GT(counts[sward::gpu::kSemanticFelled], 0u) << name;
        EXPECT_GT(counts[sward::gpu::kSemanticTrack], 5u) << name;
    }
}

// The test dataset's scene (a rover pressing ruts 0.04 m deep through grass) with a LiDAR beside the camera looking
// the way it does, every plant in view in the near LOD (the range sensors' LOD), as RangeSensorDatasets' scene.
nlohmann::json oneTileScene(bool flow) {
    nlohmann::json scene = nlohmann::json::parse(readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["lod"] = {{"near", 60}, {"mid", 70}, {"far", 80}, {"band", 2}};
    scene["camera"]["baseline"] = 0.0;
    scene["render"]["samples"] = 1;
    scene["render"]["flow"] = flow;
    scene["vehicles"][0]["rut_depth"] = 0.04;
    scene["range_sensors"] = nlohmann::json::parse(R"([{
        "name": "lidar", "preset": "VLP-16", "divergence_mrad": 0, "range_noise_m": 0, "angle_step_deg": 0.5,
        "elevations_deg": [-45, -43, -41, -39, -37, -35, -33, -31, -29, -27, -25, -23, -21, -19, -17, -15, -13, -11, -9,
                           -7, -5],
        "mount": {"position": [53.5, 46.0, 0.0], "height_above_ground": 2.2, "yaw_deg": 120.0}}])");
    return scene;
}

// 5 x 2 tiles of 10 m. The camera and the LiDAR (the same path, 2.2 m above the ground) drive east along y = 8 at
// 8 m/s, 4 m behind a rover pressing grass and ruts along y = 10.5 (the tile row y = 10..20). With load_radius 9 m
// (evict 11 m) and plants recovered 10 ticks after their last contact, the first two tile columns are evicted by frame
// 40 (x = 34); 400 m keeps every tile resident.
nlohmann::json worldScene(bool flow, double loadRadius) {
    nlohmann::json scene = nlohmann::json::parse(R"({
        "seed": 11,
        "terrain": {"size": 10, "spacing": 1, "amplitude": 1, "feature_size": 30, "octaves": 2},
        "vegetation": {"tile_size": 10, "field_size": 5},
        "world": {"tiles": [5, 2], "view_distance": 9, "memory_budget_mib": 256},
        "camera": {"path": {"points": [[2, 8], [48, 8]], "speed": 8, "height_above_ground": 2.2},
                   "look_ahead": 8, "look_at_height_above_ground": 0, "fov_y_deg": 70, "baseline": 0},
        "vehicles": [{"path": {"points": [[6, 10.5], [48, 10.5]], "speed": 8}, "weight": 2, "rut_depth": 0.04,
                      "wheel_radius": 0.4, "wheel_width": 1.0, "track_width": 1.6, "wheel_base": 1.2}],
        "interaction": {"recovery": {"rest_ticks": 10}},
        "range_sensors": [{"name": "lidar", "preset": "VLP-16", "divergence_mrad": 0, "range_noise_m": 0,
                           "angle_step_deg": 0.5, "angle_range_deg": [-60, 60], "range": [0.5, 6],
                           "elevations_deg": [-40, -35, -30, -25, -20, -15, -10],
                           "mount": {"path": {"points": [[2, 8], [48, 8]], "speed": 8,
                                              "height_above_ground": 2.2}}}],
        "render": {"samples": 1, "shadow_map_size": 256, "shadow_distance": 9},
        "lod": {"near": 8, "mid": 8.6, "far": 8.9, "band": 0.2},
        "sequence": {"frames": 60, "time_step": 0.1}
    })");
    scene["render"]["flow"] = flow;
    scene["world"]["load_radius"] = loadRadius;
    scene["world"]["evict_radius"] = loadRadius + 2.0;
    return scene;
}

// The sweep does not depend on whether flow is on: its plants and ruts are those of the frame's own tick. The cameras'
// depth and labels are bitwise the same too, so the LiDAR-to-camera-depth agreement of the datasets without flow
// (RangeSensorDatasets.LidarPointsAgreeWithTheCameraDepth*) holds with flow on.
TEST(FlowRangeDatasets, OneTileLidarPointsAreTheSameWithFlowOnOrOff) {
    const std::string off = renderDataset(oneTileScene(false), "tile-off", "3:5");
    const std::string on = renderDataset(oneTileScene(true), "tile-on", "3:5");
    expectSameRangeFiles(on, off, 3, 5);
    for (const char* file : {"depth/000004.exr", "semantic/000004.png", "instance/000004.exr", "left/000004.exr"})
        EXPECT_EQ(readFile(on + "/" + file), readFile(off + "/" + file)) << file;
}

// In a world: the sweep reads each resident tile's kept state, and every file with flow and LiDAR (colour, depth,
// labels, both flows, the range files) is bitwise the same streamed (tiles evicted behind the rover) or resident.
TEST(FlowRangeDatasets, WorldLidarPointsAreTheSameWithFlowOnOrOffStreamedOrResident) {
    const std::string off = renderDataset(worldScene(false, 9.0), "world-off", "40:42");
    const std::string streamed = renderDataset(worldScene(true, 9.0), "world-streamed", "40:42");
    const std::string resident = renderDataset(worldScene(true, 400.0), "world-resident", "40:42");
    expectSameRangeFiles(streamed, off, 40, 42);
    EXPECT_GE(expectSameRunFiles(streamed, resident), 30u);
    EXPECT_FALSE(readFile(streamed + "/flow_forward/000041.exr").empty()); // flow was written
}

} // namespace
