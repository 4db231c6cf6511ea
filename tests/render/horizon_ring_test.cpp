// A world's horizon ring (render/horizon_ring.h, issue 51 part 3): beyond world.view_distance the ground goes on as a
// coarse ring of the world's terrain, labelled ground, with no sky below the horizon, and the frames stay bitwise
// the same whether the tiles stream around the camera or all stay resident.
#include "gpu_test.h"

#include "render/scene_gpu.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"
#include "world/heightfield.h"

#include <algorithm>
#include <cmath>
#include <optional>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;
constexpr double kViewDistance = 16.0, kRingSpacing = 4.0, kWorld = 320.0;

// 8 x 8 tiles of 40 m (a 320 m world), hills of 8 m; the ring's lattice every 4th terrain vertex. The camera flies
// from the south-west corner towards the north-east one, 3 m above the ground, looking far ahead, 5 degrees down.
Scene ringWorld(double loadRadius, bool vegetation) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 7,
        "terrain": {"size": 40, "spacing": 1, "amplitude": 8, "feature_size": 70, "octaves": 3},
        "vegetation": {"tile_size": 40, "field_size": 20, "density_multiplier": 0.1},
        "world": {"tiles": [8, 8], "view_distance": 16, "memory_budget_mib": 512, "horizon": {"spacing": 4}},
        "camera": {"path": {"points": [[12, 10], [200, 198]], "speed": 10, "height_above_ground": 3},
                   "look_ahead": 120, "look_at_height_above_ground": -8, "fov_y_deg": 40},
        "render": {"shadow_map_size": 256, "shadow_distance": 20},
        "lod": {"near": 4, "mid": 8, "far": 12, "band": 2}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 10.0;
    Scene scene = parseScene(json, "ring world");
    scene.vegetationEnabled = vegetation;
    return scene;
}

struct RingFlight {
    std::vector<FrameImages> frames;
    std::vector<Camera> cameras;
    uint64_t evicted = 0;
    uint32_t ringTriangles = 0;
};

RingFlight fly(Context& ctx, double loadRadius, bool vegetation, const std::vector<double>& times) {
    SceneResources r = buildSceneResources(ringWorld(loadRadius, vegetation), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::None);
    OffscreenFrame target(ctx, kWidth, kHeight, 1);
    RingFlight run;
    for (size_t f = 0; f < times.size(); ++f) {
        const Camera camera = sceneCamera(r.scene, cameraGround(r.scene, times[f]), kWidth, kHeight, times[f]);
        const glm::dvec2 xy(camera.position);
        r.world->waitFor({&xy, 1});
        syncWorldTiles(*gpu.renderer, *r.world);
        run.frames.push_back(target.render(*gpu.renderer, camera, times[f], uint32_t(f)));
        run.cameras.push_back(camera);
    }
    run.evicted = r.world->stats().evicted;
    run.ringTriangles = gpu.renderer->horizonTriangles();
    return run;
}

uint32_t semantic(uint32_t label) {
    return label >> gpu::kInstanceBits;
}

// The drawn surfaces, modelled independently of the renderer: the tiles' terrain (the whole world's lattice in one
// heightfield) within the view distance of the camera, and beyond it every 4th of its samples (the ring's lattice).
struct WorldModel {
    Heightfield fine, coarse;
    explicit WorldModel(const Scene& scene) {
        ProceduralTerrainParams t = scene.terrain.procedural;
        t.size = float(kWorld);
        fine = makeProceduralTerrain(t);
        const uint32_t k = uint32_t(kRingSpacing), n = (fine.columns() - 1) / k + 1;
        std::vector<float> heights;
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) heights.push_back(fine.sample(k * i, k * j));
        coarse = Heightfield(n, n, float(kRingSpacing), glm::vec2(0.0f), std::move(heights));
    }
    enum class Hit { Sky, Tiles, Rim, Ring };
    // What the ray through pixel (u, v) meets first, and its planar depth.
    Hit trace(const Camera& c, double u, double v, double& depth) const {
        const glm::dvec3 ray = c.ray(u, v), dir = glm::normalize(ray);
        const double horizontal = glm::length(glm::dvec2(dir));
        const double disc = kViewDistance / horizontal; // the ray's length to the disc's edge
        if (std::optional<double> t = fine.raycast(c.position, dir, disc)) {
            depth = *t / glm::length(ray);
            return Hit::Tiles;
        }
        std::optional<double> t = coarse.raycast(c.position, dir, 1000.0);
        if (!t || *t < disc) { // the ring's parts inside the disc are not drawn: does it meet the ring beyond?
            const glm::dvec3 from = c.position + disc * dir;
            const std::optional<double> rest = coarse.raycast(from, dir, 1000.0);
            if (!rest) return Hit::Sky;
            t = disc + *rest;
        }
        depth = *t / glm::length(ray);
        // Within a ring cell's diagonal of the disc the ring's rim is sunk (horizon_ring.glsl): no exact depth there.
        return *t * horizontal < kViewDistance + 2.0 * kRingSpacing * std::sqrt(2.0) ? Hit::Rim : Hit::Ring;
    }
};

} // namespace

TEST_F(GpuTest, HorizonRingFramesAreBitwiseTheSameStreamedOrResident) {
    const std::vector<double> times{0.0, 6.0, 12.0, 18.0}; // 180 m along the diagonal
    const RingFlight streamed = fly(*ctx, kViewDistance, true, times);
    const RingFlight resident = fly(*ctx, 600.0, true, times);
    EXPECT_GT(streamed.evicted, 0u) << "the flight must leave tiles behind";
    EXPECT_EQ(resident.evicted, 0u);
    EXPECT_EQ(streamed.ringTriangles, 80u * 80u * 2u);
    for (size_t f = 0; f < times.size(); ++f) {
        EXPECT_EQ(streamed.frames[f].rgbaHalf, resident.frames[f].rgbaHalf) << "colour, frame " << f;
        EXPECT_EQ(streamed.frames[f].depth, resident.frames[f].depth) << "depth, frame " << f;
        EXPECT_EQ(streamed.frames[f].labels, resident.frames[f].labels) << "labels, frame " << f;
        EXPECT_EQ(streamed.frames[f].normals, resident.frames[f].normals) << "normals, frame " << f;
    }
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// Against the model: no sky pixel where a ray meets the ground; ring pixels labelled ground at the ring's depth;
// sky where a ray meets nothing. Pixels whose rays half a pixel above and below meet different surfaces are left out
// (a silhouette or the disc's edge runs through them).
TEST_F(GpuTest, HorizonRingShowsGroundBelowTheHorizonAtTheRingsDepth) {
    const std::vector<double> times{0.0, 12.0};
    const RingFlight run = fly(*ctx, kViewDistance, false, times);
    const WorldModel model(ringWorld(kViewDistance, false));
    uint64_t ring = 0, sky = 0, tiles = 0, rim = 0, left = 0;
    for (size_t f = 0; f < times.size(); ++f) {
        const FrameImages& im = run.frames[f];
        for (uint32_t v = 0; v < kHeight; ++v)
            for (uint32_t u = 0; u < kWidth; ++u) {
                double depth = 0.0, above = 0.0, below = 0.0;
                const auto hit = model.trace(run.cameras[f], u + 0.5, v + 0.5, depth);
                if (model.trace(run.cameras[f], u + 0.5, v + 0.05, above) != hit ||
                    model.trace(run.cameras[f], u + 0.5, v + 0.95, below) != hit) {
                    ++left;
                    continue;
                }
                const size_t i = size_t(v) * kWidth + u;
                const std::string where =
                    "frame " + std::to_string(f) + " pixel " + std::to_string(u) + "," + std::to_string(v);
                const uint32_t label = semantic(im.labels[i]);
                if (hit == WorldModel::Hit::Sky) {
                    ++sky;
                    EXPECT_EQ(label, gpu::kSemanticSky) << where;
                    continue;
                }
                ASSERT_NE(label, gpu::kSemanticSky) << where << ": sky below the horizon";
                ASSERT_TRUE(std::isfinite(im.depth[i])) << where;
                if (hit == WorldModel::Hit::Tiles) ++tiles;
                if (hit == WorldModel::Hit::Rim) ++rim;
                if (hit != WorldModel::Hit::Ring) continue;
                ++ring;
                EXPECT_EQ(label, gpu::kSemanticGround) << where;
                EXPECT_NEAR(im.depth[i], depth, 2e-4 * depth + 0.01) << where;
            }
    }
    EXPECT_GT(ring, uint64_t(times.size()) * kWidth * kHeight / 20) << "the ring shows beyond the tiles";
    EXPECT_GT(sky, uint64_t(times.size()) * kWidth * kHeight / 10);
    EXPECT_GT(tiles, 0u);
    EXPECT_LT(left, (ring + sky + tiles + rim) / 5);
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// Without the ring ("horizon": false) nothing is drawn beyond the tiles: sky shows where the ring was.
TEST_F(GpuTest, HorizonFalseDrawsNoRing) {
    Scene scene = ringWorld(kViewDistance, false);
    scene.world.horizon = false;
    SceneResources r = buildSceneResources(scene, true, 2);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::None);
    EXPECT_EQ(gpu.renderer->horizonTriangles(), 0u);
    const Camera camera = sceneCamera(r.scene, cameraGround(r.scene, 0.0), kWidth, kHeight, 0.0);
    const glm::dvec2 xy(camera.position);
    r.world->waitFor({&xy, 1});
    syncWorldTiles(*gpu.renderer, *r.world);
    const FrameImages without = renderFrame(*ctx, *gpu.renderer, camera);
    const RingFlight with = fly(*ctx, kViewDistance, false, {0.0});
    uint64_t skyWithout = 0, skyWith = 0;
    for (size_t i = 0; i < without.labels.size(); ++i) {
        skyWithout += semantic(without.labels[i]) == gpu::kSemanticSky;
        skyWith += semantic(with.frames[0].labels[i]) == gpu::kSemanticSky;
    }
    EXPECT_GT(skyWithout, skyWith + kWidth * kHeight / 20); // where the ring was
}
