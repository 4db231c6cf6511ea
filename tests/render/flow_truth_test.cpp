// Motion ground truth (render.flow) in sward-render datasets, read back independently: the .flo files with a reader
// of our own, the KITTI PNG, EXR and masks with OpenCV, the poses from frames.jsonl. Flow of a static scene is the
// depth reprojected with the two poses; wind-moved plants move as the CPU expansion reference moves them; warping the
// next frame by the flow reproduces this one; forward and backward flows agree; shards and resumed runs write the
// same bytes.
#include "gpu_test.h"
#include "plate_gltf.h"

#include "range/plant_quads.h"
#include "scene/scene.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"
#include "shared/plant_blades.h"
#include "vegetation/expansion_reference.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>

using sward::test::readFile;
using sward::test::tempDir;

namespace {

int render(const std::string& args, std::string& err) {
    return sward::test::runSwardRender(args, err);
}

// The test dataset's scene with flow, every plant in view in the near LOD (the CPU reference's), the camera driving
// 2 m/s along a path; `wind`, `vehicle` and `moving` switch the motions on; `plate`: a 3 x 3 m plate flies through
// the view, 1.2 m above the ground.
std::string flowScene(const std::string& name, bool wind, bool vehicle, bool moving, bool plate = false) {
    nlohmann::json scene = nlohmann::json::parse(readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["flow"] = true;
    scene["lod"] = {{"near", 60}, {"mid", 70}, {"far", 80}, {"band", 2}};
    scene["wind"] = wind ? nlohmann::json{{"flutter", 0.2}} // fast sway: plant pixels move by a pixel and more
                         : nlohmann::json{{"strength", 0.0}, {"gust_strength", 0.0}, {"flutter", 0.0}};
    if (!vehicle) scene.erase("vehicles");
    if (moving) scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 2.0}};
    const std::string dir = tempDir("flow-scene-" + name), path = dir + "/scene.json";
    if (plate) {
        sward::test::writePlate(dir);
        scene["objects"] = {
            {{"name", "plate"},
             {"model", "plate.gltf"},
             {"align_to_terrain", false},
             {"path", {{"points", {{48.0, 50.0}, {54.0, 53.0}}}, {"speed", 3.0}, {"height_above_ground", 1.2}}}}};
    }
    std::ofstream(path) << scene.dump(2);
    return path;
}

struct Flo {
    int width = 0, height = 0;
    std::vector<float> uv;
    bool valid(size_t i) const { return std::abs(uv[2 * i]) < 1e9f && std::abs(uv[2 * i + 1]) < 1e9f; }
};

// Middlebury's layout, read by hand: tag, width, height, (u, v) pairs.
Flo readFlo(const std::string& path) {
    const std::string bytes = readFile(path);
    Flo flo;
    float tag = 0.0f;
    EXPECT_GE(bytes.size(), 12u) << path;
    std::memcpy(&tag, bytes.data(), 4);
    std::memcpy(&flo.width, bytes.data() + 4, 4);
    std::memcpy(&flo.height, bytes.data() + 8, 4);
    EXPECT_EQ(tag, 202021.25f);
    EXPECT_EQ(bytes.size(), 12 + size_t(flo.width) * flo.height * 8) << path;
    flo.uv.resize(size_t(flo.width) * flo.height * 2);
    std::memcpy(flo.uv.data(), bytes.data() + 12, flo.uv.size() * 4);
    return flo;
}

struct Pose {
    cv::Matx44d worldFromCamera;
    double fx, fy, cx, cy; // OpenCV convention: pixel centres at whole coordinates
};

Pose framePose(const std::string& dir, int frame) {
    std::istringstream lines(readFile(dir + "/frames.jsonl"));
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json record = nlohmann::json::parse(line);
        if (record["frame"] != frame) continue;
        Pose pose;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) pose.worldFromCamera(r, c) = record["left_pose"][r][c];
        const nlohmann::json& k = record["intrinsics"];
        pose.fx = k["fx"], pose.fy = k["fy"], pose.cx = k["cx"], pose.cy = k["cy"];
        return pose;
    }
    ADD_FAILURE() << "no record of frame " << frame;
    return {};
}

cv::Vec3d worldPoint(const Pose& pose, int x, int y, double depth) {
    const cv::Vec4d c((x - pose.cx) / pose.fx * depth, (y - pose.cy) / pose.fy * depth, depth, 1.0);
    const cv::Vec4d w = pose.worldFromCamera * c;
    return {w[0], w[1], w[2]};
}

// Pixel coordinates (centres at whole numbers) and planar depth of a world point.
cv::Vec3d project(const Pose& pose, const cv::Vec3d& world) {
    const cv::Vec4d c = pose.worldFromCamera.inv() * cv::Vec4d(world[0], world[1], world[2], 1.0);
    return {pose.fx * c[0] / c[2] + pose.cx, pose.fy * c[1] / c[2] + pose.cy, c[2]};
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    return values[std::min(values.size() - 1, size_t(p * double(values.size())))];
}

} // namespace

// A still scene seen by a moving camera: every pixel's flow is its depth reprojected into the next (and previous)
// frame's camera, and the EXR's third channel is the point's depth there.
TEST(FlowTruth, StillSceneFlowIsTheDepthReprojectedWithBothPoses) {
    const std::string out = tempDir("flow-still");
    std::string err;
    ASSERT_EQ(render(flowScene("still", false, false, true) + " --out " + out + " --frames 1:2", err), 0) << err;
    const cv::Mat depth = cv::imread(out + "/depth/000001.exr", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(depth.empty());
    const Pose here = framePose(out, 1);
    for (const auto& [folder, target] : {std::pair<std::string, int>{"flow_forward", 2}, {"flow_backward", 0}}) {
        const Flo flo = readFlo(out + "/" + folder + "/000001.flo");
        const cv::Mat exr = cv::imread(out + "/" + folder + "/000001.exr", cv::IMREAD_UNCHANGED); // B, G, R = z, v, u
        ASSERT_EQ(flo.width, depth.cols);
        ASSERT_EQ(exr.type(), CV_32FC3);
        const Pose there = framePose(out, target);
        std::vector<double> errors, depthErrors;
        double motion = 0.0;
        for (int y = 0; y < depth.rows; ++y)
            for (int x = 0; x < depth.cols; ++x) {
                const size_t i = size_t(y) * depth.cols + x;
                const float z = depth.at<float>(y, x);
                ASSERT_EQ(std::isfinite(z), flo.valid(i)) << "pixel " << x << ", " << y;
                if (!std::isfinite(z)) continue;
                const cv::Vec3d p = project(there, worldPoint(here, x, y, z));
                const double du = p[0] - x - flo.uv[2 * i], dv = p[1] - y - flo.uv[2 * i + 1];
                errors.push_back(std::hypot(du, dv));
                depthErrors.push_back(std::abs(exr.at<cv::Vec3f>(y, x)[0] - p[2]) / p[2]);
                EXPECT_EQ(exr.at<cv::Vec3f>(y, x)[2], flo.uv[2 * i]);
                motion += std::hypot(p[0] - x, p[1] - y);
            }
        ASSERT_GT(errors.size(), 10000u);
        EXPECT_GT(motion / double(errors.size()), 2.0) << "the camera must move pixels by more than a pixel";
        std::printf("%s: %zu pixels, flow error median %.2e max %.2e px, depth relative error max %.2e\n",
                    folder.c_str(), errors.size(), percentile(errors, 0.5), percentile(errors, 1.0),
                    percentile(depthErrors, 1.0));
        EXPECT_LT(percentile(errors, 1.0), 1e-3);
        EXPECT_LT(percentile(depthErrors, 1.0), 1e-5);
    }
}

namespace {

// A Möller-Trumbore hit of the ray o + t d with triangle (p0, p0 + e1, p0 + e2): t and the barycentrics (b1, b2).
bool hitTriangle(const cv::Vec3d& o, const cv::Vec3d& d, const cv::Vec3d& p0, const cv::Vec3d& e1, const cv::Vec3d& e2,
                 double& t, double& b1, double& b2) {
    const cv::Vec3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-12) return false;
    const cv::Vec3d s = o - p0, q = s.cross(e1);
    b1 = s.dot(p) / det;
    b2 = d.dot(q) / det;
    t = e2.dot(q) / det;
    const double eps = 1e-6;
    return b1 >= -eps && b2 >= -eps && b1 + b2 <= 1.0 + eps && t > 0.0;
}

// Frame 1 of a flow dataset: its truth images, forward flow and pose.
struct FrameOne {
    cv::Mat depth, instance, semantic;
    Flo flo;
    Pose pose;
};

FrameOne readFrameOne(const std::string& out) {
    return {cv::imread(out + "/depth/000001.exr", cv::IMREAD_UNCHANGED),
            cv::imread(out + "/instance/000001.exr", cv::IMREAD_UNCHANGED),
            cv::imread(out + "/semantic/000001.png", cv::IMREAD_UNCHANGED), readFlo(out + "/flow_forward/000001.flo"),
            framePose(out, 1)};
}

cv::Vec3d corner(uint32_t k, const float (&a)[3][sward::PlantQuads::kTriangles]) {
    return {a[0][k], a[1][k], a[2][k]};
}

} // namespace

// Plants swaying in the wind, seen by a still camera: each plant pixel's flow is where the CPU expansion reference
// (the range sensors' plant quads: the same math as the GPU's) puts the pixel's point of its triangle at the next
// tick.
TEST(FlowTruth, WindMovedPlantsFollowTheCpuExpansionReference) {
    const std::string scenePath = flowScene("wind", true, false, false);
    const std::string out = tempDir("flow-wind");
    std::string err;
    ASSERT_EQ(render(scenePath + " --out " + out + " --frames 1:2", err), 0) << err;
    const sward::SceneResources r = sward::buildSceneResources(sward::loadScene(scenePath));
    ASSERT_TRUE(r.tile && r.atlas);
    const sward::AtlasAlpha atlas(*r.atlas);
    const FrameOne frame = readFrameOne(out);
    const cv::Mat &depth = frame.depth, &instance = frame.instance, &semantic = frame.semantic;
    const Flo& flo = frame.flo;
    const Pose& pose = frame.pose;
    const cv::Vec3d origin(pose.worldFromCamera(0, 3), pose.worldFromCamera(1, 3), pose.worldFromCamera(2, 3));
    const double time = 1 * r.scene.sequence.timeStep, next = 2 * r.scene.sequence.timeStep;
    std::vector<double> errors;
    double motion = 0.0;
    for (int y = 0; y < depth.rows; ++y)
        for (int x = 0; x < depth.cols; ++x) {
            const uint8_t c = semantic.at<uint8_t>(y, x);
            if (c < sward::gpu::kSemanticVegetation || c >= sward::gpu::kSemanticVegetation + 4) continue;
            const uint32_t plant = uint32_t(instance.at<float>(y, x)) - 1;
            const sward::FieldVegetation* field = nullptr;
            for (const sward::FieldVegetation& f : r.tile->fields)
                if (plant >= f.firstPlant && plant < f.firstPlant + f.staticRecords.size()) field = &f;
            ASSERT_NE(field, nullptr);
            const uint32_t i = plant - field->firstPlant;
            auto quadsAt = [&](double t) {
                return sward::plantQuads(atlas, r.scene.vegetation, r.scene.wind, *field, i, plant,
                                         field->dynamicRecords[i], t);
            };
            const sward::PlantQuads now = quadsAt(time), then = quadsAt(next);
            const cv::Vec3d point = worldPoint(pose, x, y, depth.at<float>(y, x));
            const cv::Vec3d ray = (point - origin) / cv::norm(point - origin);
            // The triangle the pixel shows: the one its ray meets at the truth's depth.
            double best = INFINITY, b1 = 0.0, b2 = 0.0;
            uint32_t triangle = 0;
            for (uint32_t k = 0; k < sward::PlantQuads::kTriangles; ++k) {
                double t, u, v;
                if (!hitTriangle(origin, ray, corner(k, now.p0), corner(k, now.e1), corner(k, now.e2), t, u, v))
                    continue;
                const double miss = std::abs(t - cv::norm(point - origin));
                if (miss < best) best = miss, b1 = u, b2 = v, triangle = k;
            }
            if (best > 1e-3) continue; // a plant whose triangle the float ray misses at an edge
            const cv::Vec3d moved =
                corner(triangle, then.p0) + b1 * corner(triangle, then.e1) + b2 * corner(triangle, then.e2);
            const cv::Vec3d p = project(pose, moved);
            const size_t at = size_t(y) * depth.cols + x;
            errors.push_back(std::hypot(p[0] - x - flo.uv[2 * at], p[1] - y - flo.uv[2 * at + 1]));
            motion += std::hypot(p[0] - x, p[1] - y);
        }
    ASSERT_GT(errors.size(), 2000u);
    EXPECT_GT(motion / double(errors.size()), 0.2) << "the wind must move the plants";
    std::printf("wind: %zu plant pixels, mean motion %.3f px, flow error median %.2e, 99 %% %.2e, max %.2e px\n",
                errors.size(), motion / double(errors.size()), percentile(errors, 0.5), percentile(errors, 0.99),
                percentile(errors, 1.0));
    EXPECT_LT(percentile(errors, 0.99), 1e-3);
}

// With lod.near_blades the flow of a grass pixel is where its point of its blade moves: the CPU mirror's blades
// (referenceBladeVertices) at this tick and the next.
TEST(FlowTruth, WindMovedBladesFollowTheCpuMirror) {
    const std::string scenePath = flowScene("blades", true, false, false);
    nlohmann::json json = nlohmann::json::parse(readFile(scenePath));
    json["lod"]["near_blades"] = 8;
    std::ofstream(scenePath) << json.dump(2);
    const std::string out = tempDir("flow-blades");
    std::string err;
    ASSERT_EQ(render(scenePath + " --out " + out + " --frames 1:2", err), 0) << err;
    const sward::SceneResources r = sward::buildSceneResources(sward::loadScene(scenePath));
    ASSERT_TRUE(r.tile && r.atlas);
    const sward::AtlasAlpha atlas(*r.atlas);
    const FrameOne frame = readFrameOne(out);
    const cv::Mat &depth = frame.depth, &instance = frame.instance, &semantic = frame.semantic;
    const Flo& flo = frame.flo;
    const Pose& pose = frame.pose;
    const cv::Vec3d origin(pose.worldFromCamera(0, 3), pose.worldFromCamera(1, 3), pose.worldFromCamera(2, 3));
    const double time = 1 * r.scene.sequence.timeStep, next = 2 * r.scene.sequence.timeStep;
    std::vector<double> errors;
    double motion = 0.0;
    for (int y = 0; y < depth.rows; ++y)
        for (int x = 0; x < depth.cols; ++x) {
            if (semantic.at<uint8_t>(y, x) != sward::gpu::kSemanticVegetation + 1) continue; // grass
            const uint32_t plant = uint32_t(instance.at<float>(y, x)) - 1;
            const sward::FieldVegetation* field = nullptr;
            for (const sward::FieldVegetation& f : r.tile->fields)
                if (plant >= f.firstPlant && plant < f.firstPlant + f.staticRecords.size()) field = &f;
            ASSERT_NE(field, nullptr);
            const uint32_t i = plant - field->firstPlant;
            const float aspect = atlas.baseAspects[atlas.cellOf(field->staticRecords[i].attributes)].z;
            auto bladesAt = [&](double t) {
                const sward::gpu::ExpandedPlant expanded =
                    sward::expandWholePlant(r.scene.vegetation, r.scene.wind, *field, i, field->dynamicRecords[i], t);
                return sward::referenceBladeVertices(expanded, 8, aspect);
            };
            const std::vector<glm::vec3> now = bladesAt(time), then = bladesAt(next);
            auto at = [](const std::vector<glm::vec3>& v, size_t k) { return cv::Vec3d(v[k].x, v[k].y, v[k].z); };
            const cv::Vec3d point = worldPoint(pose, x, y, depth.at<float>(y, x));
            const cv::Vec3d ray = (point - origin) / cv::norm(point - origin);
            double best = INFINITY, b1 = 0.0, b2 = 0.0;
            size_t triangle = 0;
            for (size_t k = 0; k + 2 < now.size(); k += 3) {
                double t, u, v;
                if (!hitTriangle(origin, ray, at(now, k), at(now, k + 1) - at(now, k), at(now, k + 2) - at(now, k), t,
                                 u, v))
                    continue;
                const double miss = std::abs(t - cv::norm(point - origin));
                if (miss < best) best = miss, b1 = u, b2 = v, triangle = k;
            }
            if (best > 1e-3) continue; // a blade whose triangle the float ray misses at an edge
            const cv::Vec3d moved = at(then, triangle) + b1 * (at(then, triangle + 1) - at(then, triangle)) +
                                    b2 * (at(then, triangle + 2) - at(then, triangle));
            const cv::Vec3d p = project(pose, moved);
            const size_t a = size_t(y) * depth.cols + x;
            errors.push_back(std::hypot(p[0] - x - flo.uv[2 * a], p[1] - y - flo.uv[2 * a + 1]));
            motion += std::hypot(p[0] - x, p[1] - y);
        }
    ASSERT_GT(errors.size(), 1000u);
    EXPECT_GT(motion / double(errors.size()), 0.2) << "the wind must move the blades";
    std::printf("blades: %zu grass pixels, mean motion %.3f px, flow error median %.2e, 99 %% %.2e, max %.2e px\n",
                errors.size(), motion / double(errors.size()), percentile(errors, 0.5), percentile(errors, 0.99),
                percentile(errors, 1.0));
    EXPECT_LT(percentile(errors, 0.99), 1e-3);
}

namespace {

// Frames 0..4 of the test scene with everything moving: the camera on a path, the wind, the vehicle pushing grass.
const std::string& movingDataset() {
    static const std::string out = [] {
        const std::string dir = tempDir("flow-moving");
        std::string err;
        EXPECT_EQ(render(flowScene("moving", true, true, true) + " --out " + dir + " --frames 1:3", err), 0) << err;
        return dir;
    }();
    return out;
}

cv::Vec3f bilinear(const cv::Mat& image, double x, double y) { // pixel centres at whole coordinates
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int xx, int yy) {
        const cv::Vec4f v = image.at<cv::Vec4f>(std::clamp(yy, 0, image.rows - 1), std::clamp(xx, 0, image.cols - 1));
        return cv::Vec3f(v[0], v[1], v[2]);
    };
    return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
           (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

} // namespace

// Warping frame 2 by frame 1's forward flow reproduces frame 1 on the pixels visible in both better than the flow
// moved by half a pixel in any of eight directions.
TEST(FlowTruth, WarpingTheNextFrameByTheFlowReproducesThisOneBest) {
    const std::string& out = movingDataset();
    const cv::Mat here = cv::imread(out + "/left/000001.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat there = cv::imread(out + "/left/000002.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(out + "/flow_forward_mask/000001.png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(here.type(), CV_32FC4);
    const Flo flo = readFlo(out + "/flow_forward/000001.flo");
    const double shifts[9][2] = {{0, 0},     {0.5, 0},     {-0.5, 0},   {0, 0.5},   {0, -0.5},
                                 {0.5, 0.5}, {-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}};
    double error[9] = {};
    size_t pixels = 0;
    for (int y = 0; y < here.rows; ++y)
        for (int x = 0; x < here.cols; ++x) {
            const size_t i = size_t(y) * here.cols + x;
            if (mask.at<uint8_t>(y, x) != 255) continue;
            const double tx = x + flo.uv[2 * i], ty = y + flo.uv[2 * i + 1];
            if (tx < 1 || ty < 1 || tx > here.cols - 2 || ty > here.rows - 2) continue;
            const cv::Vec4f c = here.at<cv::Vec4f>(y, x);
            for (int s = 0; s < 9; ++s) {
                const cv::Vec3f d = bilinear(there, tx + shifts[s][0], ty + shifts[s][1]) - cv::Vec3f(c[0], c[1], c[2]);
                error[s] += d.dot(d);
            }
            ++pixels;
        }
    ASSERT_GT(pixels, 5000u);
    std::printf("warp error per pixel: flow %.3e, half-pixel shifts %.3e .. %.3e\n", error[0] / pixels,
                *std::min_element(error + 1, error + 9) / pixels, *std::max_element(error + 1, error + 9) / pixels);
    for (int s = 1; s < 9; ++s) EXPECT_LT(error[0], error[s]) << "shift " << shifts[s][0] << ", " << shifts[s][1];
}

// Frame 1's forward flow and frame 2's backward flow undo each other on the pixels visible in both, where the four
// pixels around the target show the same plant or surface.
TEST(FlowTruth, ForwardAndBackwardFlowsAgree) {
    const std::string& out = movingDataset();
    const Flo forward = readFlo(out + "/flow_forward/000001.flo"),
              backward = readFlo(out + "/flow_backward/000002.flo");
    const cv::Mat mask = cv::imread(out + "/flow_forward_mask/000001.png", cv::IMREAD_UNCHANGED);
    const cv::Mat label1 = cv::imread(out + "/instance/000001.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat label2 = cv::imread(out + "/instance/000002.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat class1 = cv::imread(out + "/semantic/000001.png", cv::IMREAD_UNCHANGED);
    const cv::Mat class2 = cv::imread(out + "/semantic/000002.png", cv::IMREAD_UNCHANGED);
    std::vector<double> errors;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x) {
            const size_t i = size_t(y) * mask.cols + x;
            if (mask.at<uint8_t>(y, x) != 255) continue;
            const double tx = x + forward.uv[2 * i], ty = y + forward.uv[2 * i + 1];
            const int x0 = int(std::floor(tx)), y0 = int(std::floor(ty));
            if (x0 < 0 || y0 < 0 || x0 + 1 >= mask.cols || y0 + 1 >= mask.rows) continue;
            bool same = true;
            double bu = 0.0, bv = 0.0;
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx) {
                    const size_t j = size_t(y0 + dy) * mask.cols + x0 + dx;
                    const double w = (dx ? tx - x0 : 1 - (tx - x0)) * (dy ? ty - y0 : 1 - (ty - y0));
                    same = same && backward.valid(j) && label2.at<float>(y0 + dy, x0 + dx) == label1.at<float>(y, x) &&
                           class2.at<uint8_t>(y0 + dy, x0 + dx) == class1.at<uint8_t>(y, x);
                    bu += w * backward.uv[2 * j];
                    bv += w * backward.uv[2 * j + 1];
                }
            if (same) errors.push_back(std::hypot(forward.uv[2 * i] + bu, forward.uv[2 * i + 1] + bv));
        }
    ASSERT_GT(errors.size(), 5000u);
    std::printf("forward + backward: %zu pixels, median %.2e, 95 %% %.2e, 99 %% %.2e px\n", errors.size(),
                percentile(errors, 0.5), percentile(errors, 0.95), percentile(errors, 0.99));
    EXPECT_LT(percentile(errors, 0.5), 0.01);
    EXPECT_LT(percentile(errors, 0.95), 0.1);
}

// The three flow files hold the same flow (KITTI within its 1/64 px steps), the masks mark exactly the pixels
// with truth, and the disparity change is f B / z there - f B / z here.
TEST(FlowTruth, FlowFilesAgreeWithEachOther) {
    const std::string& out = movingDataset();
    const std::string log = readFile(out + "/frames.jsonl");
    const nlohmann::json record = nlohmann::json::parse(log.substr(0, log.find('\n')));
    const double fb = double(record["intrinsics"]["fx"]) * double(record["baseline"]);
    for (const std::string folder : {"flow_forward", "flow_backward", "flow_forward_right", "flow_backward_right"}) {
        const std::string base = out + "/" + folder;
        const Flo flo = readFlo(base + "/000002.flo");
        const cv::Mat kitti = cv::imread(base + "/000002.png", cv::IMREAD_UNCHANGED); // B, G, R = valid, v, u
        const cv::Mat exr = cv::imread(base + "/000002.exr", cv::IMREAD_UNCHANGED);
        const std::string maskFolder =
            folder.ends_with("_right") ? folder.substr(0, folder.size() - 6) + "_mask_right" : folder + "_mask";
        const cv::Mat mask = cv::imread(out + "/" + maskFolder + "/000002.png", cv::IMREAD_UNCHANGED);
        ASSERT_EQ(kitti.type(), CV_16UC3) << folder;
        ASSERT_FALSE(exr.empty() || mask.empty()) << folder;
        size_t occluded = 0, visible = 0;
        for (int y = 0; y < kitti.rows; ++y)
            for (int x = 0; x < kitti.cols; ++x) {
                const size_t i = size_t(y) * kitti.cols + x;
                const cv::Vec<uint16_t, 3> k = kitti.at<cv::Vec<uint16_t, 3>>(y, x);
                const uint8_t m = mask.at<uint8_t>(y, x);
                ASSERT_EQ(k[0] == 1, flo.valid(i));
                ASSERT_EQ(m != 0, flo.valid(i));
                ASSERT_TRUE(m == 0 || m == 128 || m == 255);
                occluded += m == 128, visible += m == 255;
                if (!flo.valid(i)) continue;
                EXPECT_LE(std::abs((k[2] - 32768.0) / 64.0 - flo.uv[2 * i]), 1.0 / 128.0 + 1e-9);
                EXPECT_LE(std::abs((k[1] - 32768.0) / 64.0 - flo.uv[2 * i + 1]), 1.0 / 128.0 + 1e-9);
                EXPECT_EQ(exr.at<cv::Vec3f>(y, x)[2], flo.uv[2 * i]);
                EXPECT_EQ(exr.at<cv::Vec3f>(y, x)[1], flo.uv[2 * i + 1]);
            }
        EXPECT_GT(visible, 2 * occluded) << folder;
        EXPECT_GT(occluded, 0u) << folder << ": the camera moves forward, so points leave the view";
    }
    const cv::Mat depth = cv::imread(out + "/depth/000002.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat exr = cv::imread(out + "/flow_forward/000002.exr", cv::IMREAD_UNCHANGED);
    const std::string pfm = readFile(out + "/disparity_change_forward/000002.pfm");
    const size_t header = pfm.size() - size_t(depth.total()) * 4;
    for (int y = 0; y < depth.rows; y += 7)
        for (int x = 0; x < depth.cols; x += 7) {
            float change;
            std::memcpy(&change, pfm.data() + header + (size_t(depth.rows - 1 - y) * depth.cols + x) * 4, 4);
            const float z = depth.at<float>(y, x), zThere = exr.at<cv::Vec3f>(y, x)[0];
            if (!std::isfinite(z)) {
                EXPECT_TRUE(std::isinf(change));
                continue;
            }
            EXPECT_NEAR(change, fb / zThere - fb / z, 1e-4 * fb / z);
        }
}

// A plate flying past a moving camera: its pixels' flow is their point moved with the plate's pose (frames.jsonl) and
// seen from the next frame's camera.
TEST(FlowTruth, MovingObjectsMoveWithTheirPose) {
    const std::string out = tempDir("flow-plate");
    std::string err;
    ASSERT_EQ(render(flowScene("plate", false, false, true, true) + " --out " + out + " --frames 1:2", err), 0) << err;
    const cv::Mat depth = cv::imread(out + "/depth/000001.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat semantic = cv::imread(out + "/semantic/000001.png", cv::IMREAD_UNCHANGED);
    const Flo flo = readFlo(out + "/flow_forward/000001.flo");
    std::istringstream lines(readFile(out + "/frames.jsonl"));
    std::map<int, cv::Matx44d> plate;
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json record = nlohmann::json::parse(line);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) plate[record["frame"]](r, c) = record["objects"][0]["pose"][r][c];
    }
    const Pose here = framePose(out, 1), there = framePose(out, 2);
    const cv::Matx44d move = plate[2] * plate[1].inv(); // world at tick 1 -> world at tick 2, for the plate's points
    std::vector<double> errors;
    double motion = 0.0;
    for (int y = 0; y < depth.rows; ++y)
        for (int x = 0; x < depth.cols; ++x) {
            if (semantic.at<uint8_t>(y, x) != sward::gpu::kSemanticObject) continue;
            const cv::Vec3d p = worldPoint(here, x, y, depth.at<float>(y, x));
            const cv::Vec4d q = move * cv::Vec4d(p[0], p[1], p[2], 1.0);
            const cv::Vec3d seen = project(there, {q[0], q[1], q[2]});
            const size_t i = size_t(y) * depth.cols + x;
            errors.push_back(std::hypot(seen[0] - x - flo.uv[2 * i], seen[1] - y - flo.uv[2 * i + 1]));
            motion += std::hypot(seen[0] - x, seen[1] - y);
        }
    ASSERT_GT(errors.size(), 300u) << "the plate must be in view";
    std::printf("plate: %zu pixels, mean motion %.2f px, flow error median %.2e max %.2e px\n", errors.size(),
                motion / double(errors.size()), percentile(errors, 0.5), percentile(errors, 1.0));
    EXPECT_GT(motion / double(errors.size()), 2.0);
    EXPECT_LT(percentile(errors, 1.0), 1e-3);
}

// A run in two shards, and a run resumed after two flow files were lost, write the very same flow files as one run.
TEST(FlowTruth, FilesAreTheSameRenderedWholeInShardsOrResumed) {
    const std::string scene = flowScene("shards", true, true, true);
    const std::string whole = tempDir("flow-whole"), sharded = tempDir("flow-sharded");
    std::string err;
    ASSERT_EQ(render(scene + " --out " + whole + " --frames 0:4", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(render(scene + " --out " + sharded + " --frames 0:4 --shard " + shard, err), 0) << err;
    auto compare = [&] {
        size_t files = 0;
        for (const auto& folder : std::filesystem::directory_iterator(whole)) {
            const std::string name = folder.path().filename().string();
            if (!folder.is_directory() || !(name.starts_with("flow") || name.starts_with("disparity_change"))) continue;
            for (const auto& file : std::filesystem::directory_iterator(folder.path())) {
                const std::string other = sharded + "/" + name + "/" + file.path().filename().string();
                EXPECT_EQ(readFile(file.path().string()), readFile(other)) << other;
                ++files;
            }
        }
        return files;
    };
    // Frames 1-3: 2 views x 2 directions x 4 files; frame 0 has no backward flow; 4 + 3 disparity changes.
    EXPECT_EQ(compare(), 3u * 16 + 8 + 4 + 3);
    std::filesystem::remove(sharded + "/flow_forward/000002.flo");
    std::filesystem::remove(sharded + "/flow_backward_mask_right/000003.png");
    ASSERT_EQ(render(scene + " --out " + sharded + " --frames 0:4", err), 0) << err;
    compare();
    EXPECT_TRUE(std::filesystem::exists(sharded + "/flow_forward/000002.flo"));
    // A complete dataset: nothing to render, nothing changed.
    ASSERT_EQ(render(scene + " --out " + sharded + " --frames 0:4", err), 0) << err;
    compare();
}
