// Ruts in a world of several tiles (issue 51, render/world_simulation.h and render/track_renderer.h): a rover
// crossing the border between tiles (1, 0) and (2, 0) at x = 40 m leaves ruts on both, drawn bitwise the same whether
// the tiles stream around the camera or all stay resident, as deep in the depth image as in the rut layer, and saved
// with the world's state.
#include "gpu_test.h"

#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "render/world_simulation.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <cmath>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;
constexpr float kRutDepth = 0.04f;
constexpr uint32_t kFrame = 120; // t = 6 s: the rover (4 m/s from x = 30 m) is at x = 54 m, out of view

// 4 x 1 tiles of 20 m, few plants; the rover drives east along y = 16 m from x = 30 m across the border at x = 40 m.
// The camera stands 4 m above the ground at (40, 10) looking 5 m ahead, at the border where the ruts cross it.
// `loadRadius` 12 m (evict 14 m) streams: tile (0, 0) is evicted once the rover has left it, (3, 0) is made resident
// as it comes; 400 m keeps every tile resident.
Scene rutWorld(double loadRadius) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 20, "spacing": 1, "amplitude": 2, "feature_size": 50, "octaves": 3},
        "vegetation": {"tile_size": 20, "field_size": 20, "density_multiplier": 0.05},
        "world": {"tiles": [4, 1], "view_distance": 12, "memory_budget_mib": 512},
        "camera": {"path": {"points": [[40, 10], [40, 19]], "speed": 0.001, "height_above_ground": 4},
                   "look_ahead": 5, "look_at_height_above_ground": 0, "fov_y_deg": 60},
        "vehicles": [{"path": {"points": [[30, 16], [75, 16]], "speed": 4}, "rut_depth": 0.04,
                      "wheel_radius": 0.4, "wheel_width": 0.4, "track_width": 1.6, "wheel_base": 1.2}],
        "render": {"shadow_map_size": 256, "shadow_distance": 12},
        "lod": {"near": 3, "mid": 6, "far": 10, "band": 2},
        "sequence": {"frames": 200, "time_step": 0.05}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 2.0;
    return parseScene(json, "rut world");
}

struct RutRun {
    FrameImages frame;
    RigCameras cameras;
    TrackBlocks tracks;
    WorldTileStats stats;
};

RutRun drive(Context& ctx, double loadRadius, const std::string& restoreFrom = {}, const std::string& saveAt = {}) {
    SceneResources r = buildSceneResources(rutWorld(loadRadius), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_TRUE(gpu.worldSimulation != nullptr);
    if (!restoreFrom.empty()) {
        EXPECT_EQ(gpu.worldSimulation->restoreState(restoreFrom), 60u);
    }
    if (!saveAt.empty()) {
        gpu.worldSimulation->runTicksBefore(60);
        gpu.worldSimulation->saveState(saveAt);
    }
    OffscreenFrame target(ctx, kWidth, kHeight, 1);
    RutRun run;
    run.frame = renderSequenceFrame(gpu, target, r, kWidth, kHeight, kFrame, 0.0, std::nullopt, run.cameras);
    run.tracks = gpu.worldSimulation->tracks().blocks();
    run.stats = r.world->stats();
    return run;
}

// The range of the rut layer's depths over the lattice vertices within 4 cells of xy: every triangle a patch draws
// under xy lies among them, whichever level of detail it is drawn at (every vertex, every 2nd or every 4th).
glm::vec2 layerRange(const GroundTracks& tracks, glm::dvec2 xy) {
    const int64_t i = int64_t(std::floor(xy.x / gpu::kTrackCell)), j = int64_t(std::floor(xy.y / gpu::kTrackCell));
    glm::vec2 range(INFINITY, -INFINITY);
    for (int64_t v = j - 4; v <= j + 5; ++v)
        for (int64_t u = i - 4; u <= i + 5; ++u)
            range = glm::vec2(std::min(range.x, tracks.depth(u, v)), std::max(range.y, tracks.depth(u, v)));
    return range;
}

} // namespace

TEST_F(GpuTest, WorldRutsCrossATileBorderBitwiseStreamedOrResidentAsDeepAsTheRutLayer) {
    const RutRun streamed = drive(*ctx, 12.0);
    const RutRun resident = drive(*ctx, 400.0);
    EXPECT_GT(streamed.stats.evicted, 0u) << "the streamed world must evict tiles";
    EXPECT_EQ(resident.stats.evicted, 0u);
    EXPECT_EQ(streamed.tracks, resident.tracks) << "the rut layer";
    EXPECT_EQ(streamed.frame.rgbaHalf, resident.frame.rgbaHalf) << "colour";
    EXPECT_EQ(streamed.frame.depth, resident.frame.depth) << "depth";
    EXPECT_EQ(streamed.frame.labels, resident.frame.labels) << "labels";

    // Each track pixel, placed in the world with the camera, lies below the lattice ground by a depth of the rut layer
    // around it (the one-tile rut test's method), the deepest by the rut depth; the ground not labelled track lies
    // within the label's depth of the unpressed ground.
    const Scene scene = rutWorld(12.0);
    GroundTracks layer;
    layer.restore(streamed.tracks);
    const Camera& camera = streamed.cameras.left;
    uint64_t west = 0, east = 0;
    float outside = 0.0f, deepest = 0.0f, groundWorst = 0.0f;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const size_t at = size_t(y) * kWidth + x;
            const uint32_t label = streamed.frame.labels[at] >> 24;
            if (label != gpu::kSemanticTrack && label != gpu::kSemanticGround) continue;
            const glm::dvec3 p = camera.position + double(streamed.frame.depth[at]) * camera.ray(x + 0.5, y + 0.5);
            const Ground ground = latticeGround(scene, glm::dvec2(p), glm::dvec2(p), 1.0);
            const float drop = ground.height(glm::vec2(p)) - float(p.z);
            if (label == gpu::kSemanticGround) {
                groundWorst = std::max(groundWorst, std::abs(drop));
                continue;
            }
            const glm::vec2 range = layerRange(layer, glm::dvec2(p));
            outside = std::max({outside, range.x - drop, drop - range.y});
            deepest = std::max(deepest, drop);
            (p.x < 40.0 ? west : east) += 1;
        }
    std::printf("track pixels: %llu on tile (1, 0), %llu on tile (2, 0); deepest %.5f m; outside the rut layer's "
                "depths by %.6f m at most; ground within %.6f m of the unpressed ground\n",
                (unsigned long long)west, (unsigned long long)east, deepest, outside, groundWorst);
    EXPECT_GT(west, 20u) << "ruts on tile (1, 0)";
    EXPECT_GT(east, 20u) << "ruts on tile (2, 0)";
    EXPECT_NEAR(deepest, kRutDepth, 2e-4);
    EXPECT_LE(outside, 2e-4f) << "the drawn ruts are not the rut layer's";
    EXPECT_LE(groundWorst, gpu::kTrackLabelDepth + 2e-4f) << "ground not labelled track lies below the ground";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// The ruts are saved with the world's state: a run restored at tick 60 (the rover half-way) draws frame 120 bitwise
// as the run that went on.
TEST_F(GpuTest, WorldRutsAreSavedAndRestoredWithTheWorldState) {
    const std::string path = ::testing::TempDir() + "/world-ruts.swardws";
    const RutRun straight = drive(*ctx, 12.0, {}, path);
    const RutRun restored = drive(*ctx, 12.0, path);
    EXPECT_FALSE(restored.tracks.empty());
    EXPECT_EQ(straight.tracks, restored.tracks);
    EXPECT_EQ(straight.frame.rgbaHalf, restored.frame.rgbaHalf);
    EXPECT_EQ(straight.frame.depth, restored.frame.depth);
    EXPECT_EQ(straight.frame.labels, restored.frame.labels);
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}
