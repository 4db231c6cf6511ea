// Range sensors in sward-render datasets, read back independently (a PLY reader of our own, OpenCV for the camera's
// truth): LiDAR points agree with the left camera's depth where both see the same surface, and the files are the
// same whether the sequence is rendered whole or in shards.
#include "gpu_test.h"

#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

using sward::test::readFile;
using sward::test::tempDir;

namespace {

int render(const std::string& args, std::string& err) {
    return sward::test::runSwardRender(args, err);
}

// The test dataset's scene with every plant in view drawn in the near LOD (the range sensors' LOD) and a LiDAR at the
// left camera's position looking the same way: no divergence, no noise, so each beam is one exact ray. `blades`:
// lod.near_blades.
std::string lidarScene(uint32_t blades = 0) {
    nlohmann::json scene = nlohmann::json::parse(readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["lod"] = {{"near", 60}, {"mid", 70}, {"far", 80}, {"band", 2}, {"near_blades", blades}};
    scene["camera"]["baseline"] = 0.0;
    scene["vehicles"][0]["rut_depth"] = 0.04; // the vehicle's wheels press ruts the LiDAR must see too
    std::vector<double> elevations; // every degree from 45 down to 5 below the horizon
    for (int e = -45; e <= -5; ++e) elevations.push_back(e);
    scene["range_sensors"] = {
        {{"name", "lidar"},
         {"preset", "VLP-16"},
         {"divergence_mrad", 0.0},
         {"range_noise_m", 0.0},
         {"angle_step_deg", 0.1},
         {"elevations_deg", elevations},
         {"mount", {{"position", {53.5, 46.0, 0.0}}, {"height_above_ground", 2.2}, {"yaw_deg", 120.0}}}}};
    const std::string path = tempDir("range-scene-" + std::to_string(blades)) + "/scene.json";
    std::ofstream(path) << scene.dump(2);
    return path;
}

struct LidarPoint {
    double wx, wy, wz;
    uint8_t semantic;
    uint32_t instance;
};

// The PLY's vertices by their header, not by sward's writer.
std::vector<LidarPoint> readPly(const std::string& path) {
    const std::string bytes = readFile(path);
    const size_t end = bytes.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    std::istringstream header(bytes.substr(0, end));
    size_t count = 0, stride = 0;
    std::map<std::string, size_t> offset;
    const std::map<std::string, size_t> sizes = {{"float", 4}, {"double", 8}, {"uchar", 1}, {"ushort", 2}, {"uint", 4}};
    for (std::string line; std::getline(header, line);) {
        std::istringstream words(line);
        std::string a, b, c;
        words >> a >> b >> c;
        if (a == "element") count = std::stoul(c);
        if (a == "property") offset[c] = stride, stride += sizes.at(b);
    }
    std::vector<LidarPoint> points(count);
    const char* data = bytes.data() + end + 11;
    EXPECT_EQ(bytes.size() - (end + 11), count * stride);
    for (size_t i = 0; i < count; ++i) {
        const char* v = data + i * stride;
        std::memcpy(&points[i].wx, v + offset["wx"], 8), std::memcpy(&points[i].wy, v + offset["wy"], 8);
        std::memcpy(&points[i].wz, v + offset["wz"], 8), std::memcpy(&points[i].semantic, v + offset["class"], 1);
        std::memcpy(&points[i].instance, v + offset["instance"], 4);
    }
    return points;
}

// LiDAR points of a sward-render dataset against its camera's truth depth where both see the same class and instance.
void expectLidarPointsAgreeWithTheCameraDepth(uint32_t blades) {
    const std::string out = tempDir("range-consistency-" + std::to_string(blades));
    std::string err;
    ASSERT_EQ(render(lidarScene(blades) + " --out " + out + " --frames 4:5 --resolution 320x240", err), 0) << err;
    const cv::Mat depth = cv::imread(out + "/depth/000004.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat semantic = cv::imread(out + "/semantic/000004.png", cv::IMREAD_UNCHANGED);
    const cv::Mat instance = cv::imread(out + "/instance/000004.exr", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(depth.empty() || semantic.empty() || instance.empty());
    std::istringstream lines(readFile(out + "/frames.jsonl"));
    nlohmann::json record;
    for (std::string line; std::getline(lines, line);)
        if (nlohmann::json j = nlohmann::json::parse(line); j["frame"] == 4) record = j;
    const nlohmann::json& k = record["intrinsics"];
    cv::Matx44d pose;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) pose(r, c) = record["left_pose"][r][c];
    const cv::Matx44d cameraFromWorld = pose.inv();

    std::vector<double> relative, plantRelative; // all points, plant points
    uint32_t plants = 0, felled = 0, ground = 0, track = 0;
    for (const LidarPoint& p : readPly(out + "/range/lidar/000004.ply")) {
        const cv::Vec4d c = cameraFromWorld * cv::Vec4d(p.wx, p.wy, p.wz, 1.0);
        if (c[2] <= 0.1) continue;
        const double u = double(k["fx"]) * c[0] / c[2] + double(k["cx"]),
                     v = double(k["fy"]) * c[1] / c[2] + double(k["cy"]);
        const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
        if (x0 < 0 || y0 < 0 || x0 + 1 >= depth.cols || y0 + 1 >= depth.rows) continue;
        // The same surface: all four pixels around the point show the point's class and instance (range sensors label
        // the ground as ground; the camera's truth calls it turf under dense plants).
        auto sameClass = [&](uint8_t pixel) {
            using namespace sward::gpu;
            return pixel == p.semantic ||
                   (p.semantic == kSemanticGround && (pixel == kSemanticTurf || pixel == kSemanticTrack));
        };
        bool same = true;
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
                same = same && sameClass(semantic.at<uint8_t>(y0 + dy, x0 + dx)) &&
                       uint32_t(instance.at<float>(y0 + dy, x0 + dx)) == p.instance;
        if (!same) continue;
        // Inverse depth is linear across the image of a plane: interpolate it bilinearly.
        const double fx = u - x0, fy = v - y0;
        auto inv = [&](int x, int y) { return 1.0 / double(depth.at<float>(y, x)); };
        const double inverse = (inv(x0, y0) * (1 - fx) + inv(x0 + 1, y0) * fx) * (1 - fy) +
                               (inv(x0, y0 + 1) * (1 - fx) + inv(x0 + 1, y0 + 1) * fx) * fy;
        relative.push_back(std::abs(c[2] * inverse - 1.0));
        const bool plant = p.semantic >= sward::gpu::kSemanticVegetation && p.semantic < sward::gpu::kSemanticObject;
        if (plant) plantRelative.push_back(relative.back());
        plants += plant;
        felled += p.semantic == sward::gpu::kSemanticFelled;
        ground += p.semantic == sward::gpu::kSemanticGround || p.semantic == sward::gpu::kSemanticTurf;
        track += p.semantic == sward::gpu::kSemanticTrack;
    }
    ASSERT_GT(relative.size(), 500u);
    auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v.empty() ? 1.0 : v[v.size() / 2];
    };
    std::printf(
        "%zu LiDAR points on surfaces the camera sees (%u plant, %u felled, %u ground, %u rut): median relative "
        "depth difference %.3g (plants %.3g)\n",
        relative.size(), plants, felled, ground, track, median(relative), median(plantRelative));
    EXPECT_LT(median(relative), 1e-4);
    EXPECT_LT(median(plantRelative), 1e-4);
    EXPECT_GT(plants, 100u);
    EXPECT_GT(ground, 100u);
    EXPECT_GT(felled, 0u); // the test scene's vehicle has felled grass by frame 4: the GPU's dynamic records are read
    EXPECT_GT(track, 0u);  // and pressed ruts, which the LiDAR sees where the camera does
}

TEST(RangeSensorDatasets, LidarPointsAgreeWithTheCameraDepthOnTheSameSurface) {
    expectLidarPointsAgreeWithTheCameraDepth(0);
}

// With lod.near_blades the range sensors cast against the blades the cameras draw (felled grass's too).
TEST(RangeSensorDatasets, LidarPointsAgreeWithTheCameraDepthOnNearBlades) {
    expectLidarPointsAgreeWithTheCameraDepth(8);
}

TEST(RangeSensorDatasets, FilesAreTheSameRenderedWholeInShardsOrResumed) {
    const std::string scene = lidarScene(), whole = tempDir("range-whole"), shards = tempDir("range-shards");
    std::string err;
    ASSERT_EQ(render(scene + " --out " + whole + " --frames 2:5 --resolution 96x72", err), 0) << err;
    ASSERT_EQ(render(scene + " --out " + shards + " --frames 2:5 --resolution 96x72 --shard 1/2", err), 0) << err;
    ASSERT_EQ(render(scene + " --out " + shards + " --frames 2:5 --resolution 96x72 --shard 0/2", err), 0) << err;
    // A frame with a range file missing is not complete: a rerun renders it again, to the same bytes.
    std::remove((shards + "/range/lidar/000003.label").c_str());
    ASSERT_EQ(render(scene + " --out " + shards + " --frames 2:5 --resolution 96x72", err), 0) << err;
    for (uint32_t frame = 2; frame < 5; ++frame)
        for (const char* extension : {".ply", ".bin", ".label"}) {
            char name[64];
            std::snprintf(name, sizeof(name), "/range/lidar/%06u%s", frame, extension);
            const std::string a = readFile(whole + name), b = readFile(shards + name);
            EXPECT_FALSE(a.empty()) << name;
            EXPECT_EQ(a, b) << name;
        }
}

} // namespace
