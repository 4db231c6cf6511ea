// Offscreen rendering: EXR files read back with OpenCV, checked against the analytic terrain; ground normals.
#include "common/half_float.h"
#include "gpu_test.h"

#include "dataset/dataset_writer.h"
#include "dataset/naming.h"
#include "io/image_files.h"
#include "render/scene_renderer.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstring>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;

// A small scene: 200 m terrain, camera 3 m above ground looking along +y at a slightly lower target.
nlohmann::json testSceneJson() {
    return nlohmann::json::parse(R"({
        "seed": 11,
        "terrain": {"size": 200, "spacing": 2, "amplitude": 10, "feature_size": 80},
        "camera": {"position": [100, 20, 0], "height_above_ground": 3,
                   "look_at": [100, 120, 0], "look_at_height_above_ground": 0, "fov_y_deg": 60}
    })");
}

Scene testScene() {
    return parseScene(testSceneJson(), "test scene");
}

class RenderTest : public GpuTest {
protected:
    FrameImages render(uint32_t samples) {
        SceneRenderer renderer(*ctx, scene, terrain, samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT);
        return renderFrame(*ctx, renderer, camera);
    }
    Scene scene = testScene();
    Ground terrain = buildTerrain(scene);
    Camera camera = sceneCamera(scene, terrain, kWidth, kHeight);
};

} // namespace

class RenderSamples : public RenderTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(RenderSamples, ExrShowsSkyAboveTerrainBelowWithAnalyticDepth) {
    FrameImages frame = render(GetParam());
    std::string dir = tempDir("render" + std::to_string(GetParam()));
    writeExrRgbaHalf(dir + "/color.exr", kWidth, kHeight, frame.rgbaHalf);
    writeExrDepth(dir + "/depth.exr", kWidth, kHeight, frame.depth);

    cv::Mat color = cv::imread(dir + "/color.exr", cv::IMREAD_UNCHANGED);
    cv::Mat depth = cv::imread(dir + "/depth.exr", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(color.empty());
    ASSERT_FALSE(depth.empty());
    ASSERT_EQ(color.type(), CV_32FC4);
    ASSERT_EQ(depth.type(), CV_32FC1);
    ASSERT_EQ(depth.cols, int(kWidth));
    ASSERT_EQ(depth.rows, int(kHeight));

    // Sky at the top: infinite depth, blue-dominated radiance (OpenCV stores BGRA).
    for (int x = 0; x < int(kWidth); x += 16) {
        EXPECT_TRUE(std::isinf(depth.at<float>(2, x)) && depth.at<float>(2, x) > 0) << "x=" << x;
        cv::Vec4f sky = color.at<cv::Vec4f>(2, x);
        EXPECT_GT(sky[0], sky[2]) << "sky should be bluer than red at x=" << x;
    }
    // Terrain at the bottom: finite depth equal to the ray cast through the rendered triangulation.
    int checked = 0;
    for (int y = int(kHeight) / 2 + 20; y < int(kHeight); y += 13) {
        for (int x = 7; x < int(kWidth); x += 29) {
            float rendered = depth.at<float>(y, x);
            ASSERT_TRUE(std::isfinite(rendered)) << "terrain pixel (" << x << "," << y << ") has no depth";
            glm::dvec3 ray = camera.ray(x + 0.5, y + 0.5);
            auto t = terrain.raycast(camera.position, glm::normalize(ray), 5000.0);
            ASSERT_TRUE(t.has_value());
            double analytic = *t / glm::length(ray); // planar depth: ray has unit camera-space z
            EXPECT_NEAR(rendered, analytic, 0.01) << "pixel (" << x << "," << y << ")";
            cv::Vec4f c = color.at<cv::Vec4f>(y, x);
            EXPECT_GT(c[1], 0.0f);
            EXPECT_EQ(c[3], 1.0f);
            ++checked;
        }
    }
    EXPECT_GT(checked, 40);
}

INSTANTIATE_TEST_SUITE_P(Msaa, RenderSamples, ::testing::Values(1u, 4u),
                         [](const auto& info) { return "x" + std::to_string(info.param); });

TEST_F(RenderTest, TwoRendersAreBitwiseIdentical) {
    FrameImages a = render(4), b = render(4);
    EXPECT_EQ(a.rgbaHalf, b.rgbaHalf);
    EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * 4));
}

namespace {

// Flat ground (amplitude 0) seen from 12 m up by a camera pitched down 31 degrees, turned off the world axes; sky
// above the terrain's far edge.
Scene flatGroundScene() {
    nlohmann::json scene = testSceneJson();
    scene["terrain"]["amplitude"] = 0;
    scene["camera"]["position"] = {90, 80, 0};
    scene["camera"]["height_above_ground"] = 12;
    scene["camera"]["look_at"] = {106, 92, 0};
    return parseScene(scene, "flat ground");
}

} // namespace

TEST_F(RenderTest, FlatGroundNormalIsWorldUpInTheCameraFrameInTheReadBackFile) {
    scene = flatGroundScene();
    terrain = buildTerrain(scene);
    camera = sceneCamera(scene, terrain, kWidth, kHeight);
    const FrameImages frame = render(1);
    const std::string dir = tempDir("normals");
    DatasetWriter writer(dir, false);
    writer.begin({{"test", 1}}, false);
    writer.writeFrame(0, frame, camera, 0.0);
    // OpenCV, not sward's reader: channels R, G, B (camera x, y, z) come back in OpenCV's B, G, R order.
    const cv::Mat file = cv::imread(dir + "/" + frameFile(kNormalFolder, 0, ".exr"), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(file.type(), CV_32FC3);
    ASSERT_EQ(file.cols, int(kWidth));
    ASSERT_EQ(file.rows, int(kHeight));

    // World up in the camera frame: row i of cameraFromWorld = camera axis i in world axes.
    const glm::dvec3 up(camera.worldFromCamera[0].z, camera.worldFromCamera[1].z, camera.worldFromCamera[2].z);
    ASSERT_LT(up.z, -0.5) << "the camera looks well down at the ground";
    ASSERT_LT(-up.y, 0.9) << "so up is not the image's up";
    uint32_t ground = 0, sky = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + x;
            const cv::Vec3f bgr = file.at<cv::Vec3f>(int(y), int(x));
            const glm::vec3 n(bgr[2], bgr[1], bgr[0]);
            ASSERT_EQ(std::memcmp(&n[0], &frame.normals[3 * i], 12), 0) << "the file holds the rendered bits";
            const uint32_t semantic = frame.labels[i] >> gpu::kInstanceBits;
            if (semantic == gpu::kSemanticSky) {
                ASSERT_EQ(n, glm::vec3(0.0f)) << "sky at (" << x << "," << y << ")";
                ++sky;
                continue;
            }
            ASSERT_EQ(semantic, gpu::kSemanticGround);
            ASSERT_NEAR(glm::length(glm::dvec3(n)), 1.0, 1e-5);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(n[c], up[c], 1e-5) << "(" << x << "," << y << ") axis " << c;
            ++ground;
        }
    EXPECT_GT(ground, kWidth * kHeight / 2);
    EXPECT_GT(sky, 0u);
}
