// Tracks seen in colour (issue 18): examples/tracks.json's rover has driven 27 m through the meadow; seen straight
// down from 8 m and obliquely at 45 degrees, the mean luminance of the track (the felled band between the wheels'
// outer edges) differs from the untouched meadow beside it by at least 10 %. Read back from sward-render's files
// as a user would: the left EXR and the depth EXR through OpenCV, each pixel placed in the world with the camera.
#include "gpu_test.h"

#include "scene/scene.h"
#include "scene/terrain.h"
#include "world/camera.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdlib>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

const std::string kScene = SWARD_EXAMPLES_DIR "/tracks/tracks.json";
constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr uint32_t kFrame = 200;        // 13.3 s: the rover is at x = 34.7 m, out of both views
constexpr double kTrackY = 37.5;        // the rover's path runs along y = 37.5 m from x = 8 m
constexpr double kTrackHalfWidth = 0.4; // wheel centres at +-0.29 m, tyre half-width and capsule radius beyond

struct Luminance {
    double track = 0.0, beside = 0.0;
    uint64_t trackPixels = 0, besidePixels = 0;
};

// Renders frame kFrame from `eye` looking at `target` (world metres) and averages the left image's luminance
// over ground points in the track band and in the bands 1-2 m beside it, between x = 12 and 28 m.
Luminance trackLuminance(const glm::dvec3& eye, const glm::dvec3& target) {
    const std::string out = tempDir("tracks");
    char args[512];
    std::snprintf(args, sizeof args, " --frames %u:%u --resolution %ux%u --camera %.4f,%.4f,%.4f --look-at %.4f,%.4f,%.4f",
                  kFrame, kFrame + 1, kWidth, kHeight, eye.x, eye.y, eye.z, target.x, target.y, target.z);
    const std::string command = SWARD_RENDER_EXE " " + kScene + args + " -q --out " + out + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    const cv::Mat left = cv::imread(out + "/left/000200.exr", cv::IMREAD_UNCHANGED);
    const cv::Mat depth = cv::imread(out + "/depth/000200.exr", cv::IMREAD_UNCHANGED);
    EXPECT_EQ(left.type(), CV_32FC4);
    EXPECT_EQ(depth.type(), CV_32FC1);
    const Scene scene = loadScene(kScene);
    const Camera camera = Camera::lookAt(eye, target, {0.0, 0.0, 1.0}, scene.camera.fovYDegrees, kWidth, kHeight);
    Luminance l;
    for (int y = 0; y < left.rows; ++y)
        for (int x = 0; x < left.cols; ++x) {
            const float d = depth.at<float>(y, x);
            if (!std::isfinite(d)) continue;
            const glm::dvec3 p = camera.position + double(d) * camera.ray(x + 0.5, y + 0.5);
            if (p.x < 12.0 || p.x > 28.0) continue;
            const cv::Vec4f bgra = left.at<cv::Vec4f>(y, x);
            const double luminance = 0.2126 * bgra[2] + 0.7152 * bgra[1] + 0.0722 * bgra[0];
            const double off = std::abs(p.y - kTrackY);
            if (off <= kTrackHalfWidth) l.track += luminance, ++l.trackPixels;
            if (off >= 1.0 && off <= 2.0) l.beside += luminance, ++l.besidePixels;
        }
    l.track /= double(std::max<uint64_t>(l.trackPixels, 1));
    l.beside /= double(std::max<uint64_t>(l.besidePixels, 1));
    return l;
}

} // namespace

TEST_F(GpuTest, ARoverTrackThroughTheMeadowShowsInColourFromAboveAndObliquely) {
    const Scene scene = loadScene(kScene);
    const Ground ground = buildTerrain(scene);
    const double z = ground.height(glm::vec2(20.0f, float(kTrackY)));
    const struct {
        const char* name;
        glm::dvec3 eye, target;
    } views[] = {{"top-down from 8 m", {20.0, kTrackY, z + 8.0}, {20.0, kTrackY + 0.01, z}},
                 {"45 degrees, 8 m up", {20.0, kTrackY - 8.0, z + 8.0}, {20.0, kTrackY, z}}};
    for (const auto& view : views) {
        const Luminance l = trackLuminance(view.eye, view.target);
        const double difference = std::abs(l.track - l.beside) / l.beside;
        std::printf("%s: track %.4f (%llu px), beside %.4f (%llu px): %.1f %%\n", view.name, l.track,
                    (unsigned long long)l.trackPixels, l.beside, (unsigned long long)l.besidePixels, 100.0 * difference);
        EXPECT_GT(l.trackPixels, 500u) << view.name;
        EXPECT_GT(l.besidePixels, 500u) << view.name;
        EXPECT_GE(difference, 0.10) << view.name;
    }
}
