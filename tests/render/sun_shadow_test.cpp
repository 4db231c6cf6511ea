// Shadows without edges (issue 18): seen from 60 m up, looking down at 45 degrees over the default meadow, the
// image shows no step in brightness where the single shadow map of before ended (an orthographic box of half-edge
// 0.575 shadow_distance around the point shadow_distance / 2 ahead of the camera, lit beyond it). The cascades reach
// where the plants end and fade out there, so the bands just inside and just outside that old box edge are equally
// bright.
#include "gpu_test.h"

#include "scene/scene.h"
#include "scene/terrain.h"
#include "test_files.h"
#include "world/camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;

// Where a ground point fell in the old shadow map: max(|x|, |y|) / half-edge in its light space (1 at the edge).
struct OldShadowBox {
    glm::dmat4 lightView{1.0};
    glm::dvec2 centre{0.0};
    double halfEdge = 0.0;

    OldShadowBox(const Camera& camera, const Scene& scene) {
        const glm::dvec3 toSun = glm::dvec3(scene.sun.direction());
        lightView = glm::lookAt(glm::dvec3(0.0), -toSun, std::abs(toSun.z) > 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1));
        const double distance = scene.render.shadowDistance;
        const glm::dvec3 c = camera.position + camera.worldFromCamera[2] * (0.5 * distance);
        centre = glm::dvec2(lightView * glm::dvec4(c, 1.0));
        halfEdge = 0.5 * distance * 1.15;
    }
    double edgeFraction(const glm::dvec3& p) const {
        const glm::dvec2 q = glm::dvec2(lightView * glm::dvec4(p, 1.0)) - centre;
        return std::max(std::abs(q.x), std::abs(q.y)) / halfEdge;
    }
};

struct Bands {
    double inside = 0.0, outside = 0.0; // mean luminance
    uint64_t insidePixels = 0, outsidePixels = 0;
};

// Mean luminance of the pixels whose surface lies within 15 % of the old box's half-edge inside and outside it,
// read back from sward-render's left EXR and depth EXR as a user would.
Bands ringBands(const std::string& out, const Camera& camera, const OldShadowBox& box) {
    const cv::Mat left = cv::imread(out + "/left/000000.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat depth = cv::imread(out + "/depth/000000.exr", cv::IMREAD_UNCHANGED);
    EXPECT_EQ(left.type(), CV_32FC4);
    EXPECT_EQ(depth.type(), CV_32FC1);
    Bands b;
    for (int y = 0; y < left.rows; ++y)
        for (int x = 0; x < left.cols; ++x) {
            const float d = depth.at<float>(y, x);
            if (!std::isfinite(d)) continue;
            const double f = box.edgeFraction(camera.position + double(d) * camera.ray(x + 0.5, y + 0.5));
            const cv::Vec4f bgra = left.at<cv::Vec4f>(y, x);
            const double luminance = 0.2126 * bgra[2] + 0.7152 * bgra[1] + 0.0722 * bgra[0];
            if (f >= 0.85 && f < 1.0) b.inside += luminance, ++b.insidePixels;
            if (f >= 1.0 && f < 1.15) b.outside += luminance, ++b.outsidePixels;
        }
    b.inside /= double(std::max<uint64_t>(b.insidePixels, 1));
    b.outside /= double(std::max<uint64_t>(b.outsidePixels, 1));
    return b;
}

} // namespace

TEST_F(GpuTest, AHighViewShowsNoShadowEdgeWhereTheOldShadowMapEnded) {
    // The meadow without its camera model and its patches: the shadows are measured, not the sensor's noise and lens
    // (an MTF blur and shot noise move the bands' means by about 0.1 % of their 3 % budget) nor where the
    // 9 m patches of denser and sparser plants happen to fall on either side of the old edge (patchiness 0.35 / 0.25:
    // steps of 2.9 / 3.3 %).
    nlohmann::json meadow = nlohmann::json::parse(test::readText(SWARD_SOURCE_DIR "/examples/meadow.json"));
    meadow["camera"].erase("sensor");
    meadow["vegetation"].erase("pattern");
    const std::string scenePath = tempDir("shadow-edge-scene") + "/meadow.json";
    std::ofstream(scenePath) << meadow.dump();
    const Scene scene = loadScene(scenePath);
    const double ground = buildTerrain(scene).height(glm::vec2(245.0f, 150.0f));
    const glm::dvec3 eye(245.0, 150.0, ground + 60.0), target = eye + glm::dvec3(0.0, 60.0, -60.0);
    const std::string out = tempDir("shadow-edge");
    char args[512];
    std::snprintf(args, sizeof args, " --frames 0:1 --resolution %ux%u --camera %.4f,%.4f,%.4f --look-at %.4f,%.4f,%.4f",
                  kWidth, kHeight, eye.x, eye.y, eye.z, target.x, target.y, target.z);
    const std::string command = SWARD_RENDER_EXE " " + scenePath + args + " -q --out " + out + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const Camera camera = Camera::lookAt(eye, target, {0.0, 0.0, 1.0}, scene.camera.fovYDegrees, kWidth, kHeight);
    const Bands b = ringBands(out, camera, OldShadowBox(camera, scene));
    const double step = std::abs(b.outside - b.inside) / b.inside;
    std::printf("old shadow box edge: inside %.4f (%llu px), outside %.4f (%llu px): step %.1f %%\n", b.inside,
                (unsigned long long)b.insidePixels, b.outside, (unsigned long long)b.outsidePixels, 100.0 * step);
    ASSERT_GT(b.insidePixels, 1000u) << "the old edge must cross the image";
    ASSERT_GT(b.outsidePixels, 1000u);
    EXPECT_LT(step, 0.03);
}
