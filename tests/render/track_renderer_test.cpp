// Ruts in bare ground (issue 18, render/track_renderer.h): examples/rover-pass.json without vegetation, its rover's
// wheels pressing 4 cm ruts with a tread. Read back from sward-render's files as a user would (depth EXR, left EXR and
// semantic PNG through OpenCV, each pixel placed in the world with the camera): behind the rover the ground lies
// the configured depth lower and is darker, in front of it the ground is untouched; and the ruts are the same bits
// from shards and from a restored state.
#include "gpu_test.h"

#include "render/session.h"
#include "scene/scene.h"
#include "scene/scene_input.h"
#include "scene/terrain.h"
#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

const std::string kScene = SWARD_TEST_DATA_DIR "/../../examples/rover-pass.json";
constexpr float kRutDepth = 0.04f; // the wheels' rut_depth in rover-pass.json
constexpr double kPathX = 250.0;   // the rover drives from (250, 199) towards +y at 2 m/s
constexpr uint32_t kFrame = 29;    // t = 1.93 s: the rover's centre is at y = 202.87 m

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    return bytes.str();
}

std::string render(const std::string& args) {
    const std::string out = tempDir("ruts");
    const std::string command =
        SWARD_RENDER_EXE " " + kScene + " --no-vegetation -q " + args + " --out " + out + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return out;
}

// Frame `frame`'s left camera from frames.jsonl: world point of pixel (x, y) at planar depth d.
struct LeftCamera {
    glm::dmat3 rotation{1.0};
    glm::dvec3 position{0.0};
    double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0;
    glm::dvec3 point(int x, int y, double d) const {
        return position + rotation * glm::dvec3((x - cx) / fx * d, (y - cy) / fy * d, d);
    }
};

LeftCamera leftCamera(const std::string& dataset, uint32_t frame) {
    std::istringstream lines(readFile(dataset + "/frames.jsonl"));
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json f = nlohmann::json::parse(line);
        if (f.at("frame") != frame) continue;
        LeftCamera c;
        const nlohmann::json& pose = f.at("left_pose");
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k) c.rotation[k][r] = pose[r][k].get<double>();
            c.position[r] = pose[r][3].get<double>();
        }
        const nlohmann::json& k = f.at("intrinsics");
        c.fx = k.at("fx"), c.fy = k.at("fy"), c.cx = k.at("cx"), c.cy = k.at("cy");
        return c;
    }
    ADD_FAILURE() << "frame " << frame << " is not in " << dataset << "/frames.jsonl";
    return {};
}

struct Band {
    double luminance = 0.0;
    uint64_t pixels = 0;
    void add(double l) { luminance += l, ++pixels; }
    double mean() const { return luminance / double(std::max<uint64_t>(pixels, 1)); }
};

} // namespace

TEST_F(GpuTest, WheelsPressRutsOfTheConfiguredDepthIntoBareGroundSeenInDepthColourAndLabels) {
    const Scene scene = loadScene(kScene);
    const Ground ground = buildTerrain(scene);
    constexpr uint32_t kWidth = 320, kHeight = 240;
    // The scene's own view, 2 m up, looking along the track at the rover.
    const glm::dvec3 eye(253.2, 198.5, ground.height(glm::vec2(253.2f, 198.5f)) + 2.0);
    const glm::dvec3 target(250.0, 203.5, ground.height(glm::vec2(250.0f, 203.5f)));
    char args[256];
    std::snprintf(args, sizeof args,
                  "--frames %u:%u --resolution %ux%u --camera %.4f,%.4f,%.4f --look-at %.4f,%.4f,%.4f", kFrame,
                  kFrame + 1, kWidth, kHeight, eye.x, eye.y, eye.z, target.x, target.y, target.z);
    const std::string out = render(args);
    const cv::Mat depth = cv::imread(out + "/depth/000029.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat left = cv::imread(out + "/left/000029.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat semantic = cv::imread(out + "/semantic/000029.png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_32FC1);
    ASSERT_EQ(left.type(), CV_32FC4);
    ASSERT_EQ(semantic.type(), CV_8U);
    const LeftCamera camera = leftCamera(out, kFrame);

    const double roverY = 199.0 + 2.0 * kFrame * scene.sequence.timeStep;
    float deepest = 0.0f, groundWorst = 0.0f;
    uint64_t track = 0, trackAhead = 0, lugs = 0;
    Band pressed, beside, ahead;
    for (int y = 0; y < depth.rows; ++y)
        for (int x = 0; x < depth.cols; ++x) {
            const float d = depth.at<float>(y, x);
            const int label = semantic.at<uint8_t>(y, x);
            if (!std::isfinite(d) || label == int(gpu::kSemanticObject)) continue;
            const glm::dvec3 p = camera.point(x, y, d);
            // How far below the unpressed ground the surface seen here lies.
            const float drop = ground.height(glm::vec2(p)) - float(p.z);
            const cv::Vec4f bgra = left.at<cv::Vec4f>(y, x);
            const double luminance = 0.2126 * bgra[2] + 0.7152 * bgra[1] + 0.0722 * bgra[0];
            const double off = std::abs(p.x - kPathX);
            if (label == int(gpu::kSemanticTrack)) {
                ++track;
                deepest = std::max(deepest, drop);
                lugs += drop > kRutDepth - 0.005f;
                if (p.y > roverY + 0.6) ++trackAhead;
                if (p.y > roverY - 2.5 && p.y < roverY - 0.6) pressed.add(luminance);
            } else {
                ASSERT_EQ(label, int(gpu::kSemanticGround)) << x << "," << y;
                groundWorst = std::max(groundWorst, std::abs(drop));
                if (off > 0.6 && off < 1.5 && p.y > roverY - 2.5 && p.y < roverY - 0.6) beside.add(luminance);
                if (off < 0.4 && p.y > roverY + 0.8 && p.y < roverY + 3.0) ahead.add(luminance);
            }
        }
    std::printf("track pixels %llu (%llu at the lugs' depth), deepest %.5f m, ground pixels within %.5f m of the "
                "unpressed ground; luminance: rut %.4f, beside %.4f, ahead %.4f\n",
                (unsigned long long)track, (unsigned long long)lugs, deepest, groundWorst, pressed.mean(),
                beside.mean(), ahead.mean());
    EXPECT_GT(track, 500u);
    EXPECT_NEAR(deepest, kRutDepth, 2e-4) << "the ruts are not the configured depth";
    EXPECT_GT(lugs, track / 5) << "too few pixels at the rut's full depth";
    EXPECT_LE(groundWorst, gpu::kTrackLabelDepth + 2e-4f) << "ground not labelled track lies below the ground";
    EXPECT_EQ(trackAhead, 0u) << "ruts in front of the rover";
    ASSERT_GT(pressed.pixels, 100u);
    ASSERT_GT(beside.pixels, 100u);
    ASSERT_GT(ahead.pixels, 20u);
    EXPECT_GT(std::abs(pressed.mean() - beside.mean()) / beside.mean(), 0.10);
    EXPECT_GT(std::abs(pressed.mean() - ahead.mean()) / ahead.mean(), 0.10);
}

TEST_F(GpuTest, RutsAreTheSameBitsFromShardsAndFromARestoredState) {
    const std::string full = render("--frames 0:12 --resolution 96x64 --samples 1");
    const std::string sharded = tempDir("ruts-shards");
    for (const char* shard : {"0/2", "1/2"}) {
        const std::string command = SWARD_RENDER_EXE " " + kScene +
                                    " --no-vegetation -q --frames 0:12 --resolution "
                                    "96x64 --samples 1 --shard " +
                                    std::string(shard) + " --out " + sharded + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
    }
    for (const char* file : {"depth/000011.exr", "left/000011.exr", "semantic/000011.png", "normal/000011.exr"}) {
        const std::string a = readFile(full + "/" + file);
        EXPECT_FALSE(a.empty()) << file;
        EXPECT_EQ(a, readFile(sharded + "/" + file)) << file;
    }

    // The Python module's path: a state saved after 6 ticks, restored into a new session, continues bitwise.
    const SceneInput input{.path = kScene, .overrides = R"({"render.resolution": [96, 64], "render.samples": 1})"};
    const SessionOptions options{.validation = true, .vegetation = false};
    Session straight(loadSceneInput(input), options);
    straight.step(6);
    const std::string state = tempDir("ruts-state") + "/state.bin";
    straight.saveState(state);
    straight.step(4);
    const SessionFrame expected = straight.render();
    Session resumed(loadSceneInput(input), options);
    resumed.restoreState(state);
    resumed.step(4);
    const SessionFrame again = resumed.render();
    EXPECT_EQ(again.frame, 10u);
    EXPECT_EQ(expected.images.depth, again.images.depth);
    EXPECT_EQ(expected.images.rgbaHalf, again.images.rgbaHalf);
    EXPECT_EQ(expected.images.labels, again.images.labels);
    uint64_t trackPixels = 0;
    for (uint32_t label : again.images.labels) trackPixels += (label >> gpu::kInstanceBits) == gpu::kSemanticTrack;
    EXPECT_GT(trackPixels, 0u) << "no rut in view: the test shows nothing";
    EXPECT_EQ(resumed.device().validationMessageCount(), 0u);
}
