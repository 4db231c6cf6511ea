// Drawing a world of several tiles (issue 15, part 3): frames of a flight across tiles are bitwise the same whether
// the tiles come and go around the camera (streamed) or all stay resident, and the tiles meet without a gap.
#include "gpu_test.h"
#include "world_flight.h"

#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 96;

// 4 x 4 tiles of 40 m; the camera flies diagonally across six of them, 3 m above the ground, looking ahead.
// `loadRadius` 35 m streams (tiles come and go); 400 m keeps the whole world resident. Both draw out to 35 m.
Scene smallWorld(double loadRadius) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 11,
        "terrain": {"size": 40, "spacing": 1, "amplitude": 5, "feature_size": 50, "octaves": 3},
        "vegetation": {"tile_size": 40, "field_size": 20},
        "world": {"tiles": [4, 4], "view_distance": 35},
        "camera": {"path": {"points": [[10, 8], [150, 130]], "speed": 12, "height_above_ground": 3},
                   "look_ahead": 14, "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "render": {"shadow_map_size": 256, "shadow_distance": 25},
        "lod": {"near": 4, "mid": 10, "far": 24, "band": 2}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 10.0;
    json["world"]["memory_budget_mib"] = 512;
    return parseScene(json, "small world");
}

using Flight = sward::test::WorldFlight;

Flight fly(Context& ctx, double loadRadius, uint32_t frames) {
    return sward::test::flyWorld(ctx, smallWorld(loadRadius), kWidth, kHeight, frames);
}

} // namespace

TEST_F(GpuTest, WorldFramesAreBitwiseTheSameStreamedOrResident) {
    constexpr uint32_t kFrames = 12; // 12 s at 12 m/s: 144 m, across the diagonal tiles (0,0) .. (2,2)
    const Flight streamed = fly(*ctx, 35.0, kFrames);
    const Flight resident = fly(*ctx, 400.0, kFrames);
    EXPECT_GT(streamed.evicted, 0u) << "the flight must leave tiles behind";
    EXPECT_EQ(resident.evicted, 0u);
    EXPECT_EQ(resident.mostTilesDrawn, 16u);
    EXPECT_LT(streamed.mostTilesDrawn, 16u);
    uint64_t plantPixels = 0;
    for (uint32_t f = 0; f < kFrames; ++f) {
        const FrameImages& a = streamed.frames[f];
        const FrameImages& b = resident.frames[f];
        EXPECT_EQ(a.rgbaHalf, b.rgbaHalf) << "left colour, frame " << f;
        EXPECT_EQ(a.rightRgbaHalf, b.rightRgbaHalf) << "right colour, frame " << f;
        EXPECT_EQ(a.depth, b.depth) << "depth, frame " << f;
        EXPECT_EQ(a.labels, b.labels) << "labels, frame " << f;
        for (uint32_t label : a.labels) {
            const uint32_t semantic = label >> gpu::kInstanceBits;
            plantPixels += semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject;
        }
    }
    EXPECT_GT(plantPixels, uint64_t(kFrames) * kWidth * kHeight / 20) << "the flight sees grass";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// In a world, instance ids count within a tile and the truth names the tile: every plant pixel's tile label is the
// tile its surface lies over (a blade leaning over the border lies within a metre of it), every other pixel has none.
TEST_F(GpuTest, WorldPlantPixelsNameTheirTile) {
    const Flight flight = fly(*ctx, 35.0, 6);
    constexpr double kTile = 40.0;
    std::set<uint32_t> seen;
    uint64_t plants = 0, inside = 0;
    for (size_t f = 0; f < flight.frames.size(); ++f) {
        const FrameImages& im = flight.frames[f];
        ASSERT_EQ(im.tiles.size(), im.labels.size());
        for (uint32_t v = 0; v < kHeight; ++v)
            for (uint32_t u = 0; u < kWidth; ++u) {
                const size_t i = size_t(v) * kWidth + u;
                const uint32_t semantic = im.labels[i] >> gpu::kInstanceBits;
                const bool plant = semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject;
                if (!plant) {
                    ASSERT_EQ(im.tiles[i], 0u) << "frame " << f << " pixel " << u << "," << v;
                    continue;
                }
                ASSERT_GE(im.tiles[i], 1u);
                const uint32_t tile = im.tiles[i] - 1, tx = tile % 4, ty = tile / 4;
                seen.insert(tile);
                const Camera& c = flight.cameras[f];
                const glm::dvec3 p = c.position + double(im.depth[i]) * c.ray(u + 0.5, v + 0.5);
                const double dx = std::max({0.0, tx * kTile - p.x, p.x - (tx + 1) * kTile});
                const double dy = std::max({0.0, ty * kTile - p.y, p.y - (ty + 1) * kTile});
                ASSERT_LT(std::max(dx, dy), 1.0) << "a plant of tile " << tile << " seen at " << p.x << ", " << p.y;
                ++plants;
                inside += dx == 0.0 && dy == 0.0;
            }
    }
    EXPECT_GE(seen.size(), 3u) << "the flight crosses several tiles";
    EXPECT_GT(double(inside), 0.99 * double(plants));
}

// The camera looks down across the corner where four tiles meet: every pixel is ground or plant, so the ground has
// no crack along the seams (sky would show through).
TEST_F(GpuTest, WorldTilesMeetWithoutACrack) {
    Scene scene = smallWorld(60.0);
    scene.camera.hasPath = false;
    scene.camera.position = glm::dvec3(76.0, 76.0, 0.0);
    scene.camera.useHeightAboveGround = true;
    scene.camera.heightAboveGround = 12.0;
    scene.camera.lookAt = glm::dvec3(80.5, 80.5, 0.0);
    scene.camera.lookAtUsesGround = true;
    SceneResources r = buildSceneResources(scene, true, 2);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::None);
    const Camera camera = sceneCamera(r.scene, cameraGround(r.scene, 0.0), kWidth, kHeight);
    const glm::dvec2 xy(camera.position);
    r.world->waitFor({&xy, 1});
    syncWorldTiles(*gpu.renderer, *r.world);
    ASSERT_GE(gpu.renderer->tileCount(), 4u);
    const FrameImages images = renderFrame(*ctx, *gpu.renderer, camera);
    uint32_t sky = 0;
    for (uint32_t label : images.labels) sky += (label >> gpu::kInstanceBits) == gpu::kSemanticSky;
    EXPECT_EQ(sky, 0u) << "the view is below the horizon: a sky pixel is a crack between tiles";
    // Nor a seam of another kind: the turf (the cover's look of the ground) frays across a border as anywhere else.
    // Its lookup is displaced by up to half a metre; where that fell off the drawn tile it once read no cover, a line
    // of bare `ground` (labels and colour) along every border: 60 % of the ground pixels within 0.25 m of x or y = 80.
    uint32_t nearBare = 0, near = 0, awayBare = 0, away = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + x;
            const uint32_t s = images.labels[i] >> gpu::kInstanceBits;
            if (s != gpu::kSemanticGround && s != gpu::kSemanticTurf) continue;
            const glm::dvec3 p = camera.position + double(images.depth[i]) * camera.ray(x + 0.5, y + 0.5);
            const double border = std::min(std::abs(p.x - 80.0), std::abs(p.y - 80.0));
            if (border < 0.25) ++near, nearBare += s == gpu::kSemanticGround;
            if (border > 1.0 && border < 4.0) ++away, awayBare += s == gpu::kSemanticGround;
        }
    ASSERT_GT(near, 20u);
    ASSERT_GT(away, 200u);
    const double nearShare = double(nearBare) / near, awayShare = double(awayBare) / away;
    std::printf("bare ground within 0.25 m of a border: %.3f of %u ground pixels; 1-4 m from it: %.3f of %u\n",
                nearShare, near, awayShare, away);
    EXPECT_LT(nearShare, awayShare + 0.1) << "a line of bare ground along the tile borders";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

namespace {

// A wide-wheeled rover drives a track into tile (0, 0) along y = 16, then leaves east (the small world's 40 m tiles, time step
// 0.05 s). The camera flies beside the track, east to x = 140 and back 8 m further north, looking along the track on
// the way back.
// With load_radius 20 m (evict 25 m) tile (0, 0) is evicted while both are away (once its plants have recovered) and
// generated again, from its kept state, for the camera's return; with 400 m every tile stays resident.
Scene trackWorld(double loadRadius, float weight) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 11,
        "terrain": {"size": 40, "spacing": 1, "amplitude": 2, "feature_size": 50, "octaves": 3},
        "vegetation": {"tile_size": 40, "field_size": 20},
        "world": {"tiles": [4, 4], "view_distance": 20, "memory_budget_mib": 512},
        "camera": {"path": {"points": [[18, 12], [140, 12], [140, 20], [18, 20]], "speed": 10, "height_above_ground": 2.5},
                   "look_ahead": 10, "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "vehicles": [{"path": {"points": [[4, 16], [36, 16], [100, 16]], "speed": 4},
                      "wheel_radius": 0.4, "wheel_width": 1.0, "track_width": 1.6, "wheel_base": 1.2}],
        "render": {"shadow_map_size": 256, "shadow_distance": 20},
        "lod": {"near": 4, "mid": 10, "far": 16, "band": 2},
        "sequence": {"frames": 600, "time_step": 0.05}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 5.0;
    json["vehicles"][0]["weight"] = weight;
    return parseScene(json, "track world");
}

struct TrackRun {
    std::vector<FrameImages> frames;
    WorldTileStats stats;
    uint64_t contacts = 0;
};

TrackRun driveTrack(Context& ctx, double loadRadius, float weight, const std::vector<uint32_t>& frames) {
    SceneResources r = buildSceneResources(trackWorld(loadRadius, weight), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_TRUE(gpu.worldSimulation != nullptr);
    OffscreenFrame target(ctx, kWidth, kHeight, 1);
    TrackRun run;
    for (uint32_t frame : frames) {
        RigCameras cameras;
        run.frames.push_back(renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, std::nullopt, cameras));
    }
    run.stats = r.world->stats();
    run.contacts = gpu.worldSimulation->contacts();
    return run;
}

} // namespace

// A track made in a tile survives the tile's eviction and generation again: the frames are bitwise those of a world
// whose tiles all stay resident, and the track is there (the same frames without the rover's weight differ).
TEST_F(GpuTest, WorldTrackSurvivesEvictionBitwiseAsIfResident) {
    // 160: the camera is away east while the rover finishes its track; 470: the camera is back, looking along it
    // (tile (0, 0) was evicted near tick 305 and made resident again near tick 404).
    const std::vector<uint32_t> frames{160, 470};
    const TrackRun streamed = driveTrack(*ctx, 20.0, 2.0f, frames);
    const TrackRun resident = driveTrack(*ctx, 400.0, 2.0f, frames);
    const TrackRun untouched = driveTrack(*ctx, 20.0, 0.0f, frames);
    EXPECT_GT(streamed.stats.restored, 0u) << "tile (0, 0) must come back from its kept state";
    EXPECT_EQ(resident.stats.evicted, 0u);
    EXPECT_GT(streamed.contacts, 1000u);
    EXPECT_EQ(streamed.contacts, resident.contacts);
    for (size_t f = 0; f < frames.size(); ++f) {
        EXPECT_EQ(streamed.frames[f].rgbaHalf, resident.frames[f].rgbaHalf) << "colour, frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].depth, resident.frames[f].depth) << "depth, frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].labels, resident.frames[f].labels) << "labels, frame " << frames[f];
    }
    uint64_t changed = 0;
    for (size_t i = 0; i < streamed.frames[1].depth.size(); ++i)
        changed += streamed.frames[1].depth[i] != untouched.frames[1].depth[i];
    EXPECT_GT(changed, uint64_t(kWidth) * kHeight / 100) << "the track shows when the camera is back";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// Save / restore covers the whole world: a run restored from the state saved at tick 200 (tracks in resident and
// recovering tiles) renders frame 470 bitwise as the run that went on without stopping.
TEST_F(GpuTest, WorldStateSavedMidTrackRestoresToTheSameFrames) {
    const std::string path = ::testing::TempDir() + "/world-track.swardws";
    FrameImages straight, restored;
    {
        SceneResources r = buildSceneResources(trackWorld(20.0, 2.0f), true, 2);
        SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
        OffscreenFrame target(*ctx, kWidth, kHeight, 1);
        gpu.worldSimulation->runTicksBefore(200);
        gpu.worldSimulation->saveState(path);
        RigCameras cameras;
        straight = renderSequenceFrame(gpu, target, r, kWidth, kHeight, 470, 0.0, std::nullopt, cameras);
    }
    {
        SceneResources r = buildSceneResources(trackWorld(20.0, 2.0f), true, 2);
        SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
        OffscreenFrame target(*ctx, kWidth, kHeight, 1);
        EXPECT_EQ(gpu.worldSimulation->restoreState(path), 200u);
        RigCameras cameras;
        restored = renderSequenceFrame(gpu, target, r, kWidth, kHeight, 470, 0.0, std::nullopt, cameras);
    }
    EXPECT_EQ(straight.rgbaHalf, restored.rgbaHalf);
    EXPECT_EQ(straight.depth, restored.depth);
    EXPECT_EQ(straight.labels, restored.labels);
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}
