// Motion ground truth (render.flow) in a world of several tiles (issue 51): a rover presses the grass of a strip of
// 20 m tiles with the camera following it across a tile border; the flow of every ground pixel is its depth
// reprojected into the previous and the next tick's camera, the flow of every plant pixel is where the CPU expansion
// reference puts its point with the plant's state at those ticks (read back from the world's simulation), and all of
// it is bitwise the same whether the tiles stream around the camera and the rover or all stay resident.
#include "gpu_test.h"

#include "range/plant_quads.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;

// 4 x 1 tiles of 20 m. A light rover (it bends the grass, which springs back, and fells none) drives east along
// y = 10 from x = 12 at 0.4 m a frame; the camera follows 4 m behind, 1.6 m up, looking ahead: at frame 22 it looks
// across the border x = 20 at both tiles and the fresh track. Every plant within reach is drawn in the near LOD (the
// CPU reference's quads), swaying in the wind. `loadRadius` 9 m (evict 12 m) streams: tile (0, 0), recovered 20 ticks
// after the rover's last contact, is evicted behind the camera while frame 61 renders (its next tick prepared), tile
// (3, 0) made resident for the rover while frame 97 renders; 200 m keeps every tile resident.
Scene flowWorld(double loadRadius) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 20, "spacing": 1, "amplitude": 1.5, "feature_size": 30, "octaves": 2},
        "vegetation": {"tile_size": 20, "field_size": 10},
        "world": {"tiles": [4, 1], "view_distance": 9, "memory_budget_mib": 256},
        "camera": {"path": {"points": [[8, 10], [79, 10]], "speed": 4, "height_above_ground": 1.6},
                   "look_ahead": 5, "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "vehicles": [{"path": {"points": [[12, 10], [79, 10]], "speed": 4}, "weight": 0.4,
                      "wheel_radius": 0.4, "wheel_width": 0.8, "track_width": 1.6, "wheel_base": 1.2}],
        "wind": {"flutter": 0.2},
        "interaction": {"recovery": {"rest_ticks": 20}},
        "render": {"flow": true, "shadow_map_size": 256, "shadow_distance": 9},
        "lod": {"near": 7, "mid": 7.5, "far": 8, "band": 1},
        "sequence": {"frames": 200, "time_step": 0.1}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 3.0;
    return parseScene(json, "flow world");
}

using Key = std::pair<int32_t, int32_t>;           // (x, y)
using PlantStates = std::map<Key, VegetationTile>; // the resident tiles' plants, with their dynamic records then

struct FlowRun {
    std::map<uint32_t, FrameImages> frames;
    std::map<uint32_t, PlantStates> after; // after frame f renders: the plants' state of tick f + 1
    WorldTileStats stats;
    std::set<Key> residentChanged; // tiles made resident or evicted while a run of frames rendered
};

// Renders `frames` in order (the rendered runs of consecutive frames), reading the plants' state back after each when
// `states` (WorldSimulation::saveState reads every simulated tile back into the world's CPU tiles).
FlowRun fly(Context& ctx, double loadRadius, const std::vector<uint32_t>& frames, bool states) {
    SceneResources r = buildSceneResources(flowWorld(loadRadius), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_TRUE(gpu.worldSimulation != nullptr);
    OffscreenFrame target(ctx, kWidth, kHeight, 1, true);
    FlowRun run;
    std::set<Key> resident;
    for (size_t k = 0; k < frames.size(); ++k) {
        const uint32_t frame = frames[k];
        RigCameras cameras;
        run.frames[frame] = renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, std::nullopt, cameras);
        const std::vector<TileCoord> now = r.world->residentTiles();
        std::set<Key> keys;
        for (TileCoord c : now) keys.insert(Key(c.x, c.y));
        if (k > 0 && frames[k - 1] + 1 == frame) // changed between two consecutive frames' ticks
            for (const std::set<Key>* set : {&keys, &resident})
                for (const Key& key : *set)
                    if (keys.contains(key) != resident.contains(key)) run.residentChanged.insert(key);
        resident = keys;
        if (!states) continue;
        gpu.worldSimulation->saveState(::testing::TempDir() + "/world-flow.swardws");
        for (TileCoord c : now) run.after[frame].emplace(Key(c.x, c.y), r.world->find(c)->vegetation);
    }
    run.stats = r.world->stats();
    return run;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    return values[std::min(values.size() - 1, size_t(p * double(values.size())))];
}

// A Möller-Trumbore hit of the ray o + t d with triangle (p0, p0 + e1, p0 + e2): t and the barycentrics (b1, b2).
bool hitTriangle(glm::dvec3 o, glm::dvec3 d, glm::dvec3 p0, glm::dvec3 e1, glm::dvec3 e2, double& t, double& b1,
                 double& b2) {
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12) return false;
    const glm::dvec3 s = o - p0, q = glm::cross(s, e1);
    b1 = glm::dot(s, p) / det;
    b2 = glm::dot(d, q) / det;
    t = glm::dot(e2, q) / det;
    const double eps = 1e-6;
    return b1 >= -eps && b2 >= -eps && b1 + b2 <= 1.0 + eps && t > 0.0;
}

glm::dvec3 corner(uint32_t k, const float (&a)[3][PlantQuads::kTriangles]) {
    return {a[0][k], a[1][k], a[2][k]};
}

struct FlowErrors {
    std::vector<double> ground, plants;
    std::set<uint32_t> plantTiles; // tile labels of the checked plant pixels
    uint64_t sky = 0, movedPlants = 0;
};

Camera cameraAt(const Scene& scene, uint32_t frame) {
    const double time = double(frame) * scene.sequence.timeStep;
    return sceneRig(scene, cameraGround(scene, time), {}, kWidth, kHeight, time).left;
}

// The plant pixel's point moved from its state in `here` at frame f to its state in `there` at frame `other`, seen by
// `to`: that pixel's expected flow (target minus pixel centre), or nothing when the pixel's triangle cannot be found
// (a float ray missing the triangle at an edge, or a plant drawn in the cross-fade to the mid LOD).
std::optional<glm::dvec2> plantFlow(const Scene& scene, const AtlasAlpha& atlas, const Camera& from, const Camera& to,
                                    uint32_t u, uint32_t v, double depth, uint32_t label, uint32_t tile, uint32_t frame,
                                    uint32_t other, const PlantStates& here, const PlantStates& there, bool& moved) {
    const Key key(int32_t((tile - 1) % scene.world.tilesX), int32_t((tile - 1) / scene.world.tilesX));
    const auto a = here.find(key), b = there.find(key);
    if (a == here.end() || b == there.end()) {
        ADD_FAILURE() << "frame " << frame << " draws tile " << key.first << ", " << key.second
                      << " which was not resident around it";
        return std::nullopt;
    }
    const uint32_t plant = (label & ((1u << gpu::kInstanceBits) - 1u)) - 1u;
    size_t f = 0;
    while (f < a->second.fields.size() && plant >= a->second.fields[f].firstPlant + a->second.fields[f].plantCount())
        ++f;
    if (f == a->second.fields.size()) {
        ADD_FAILURE() << "plant " << plant << " is not in tile " << key.first << ", " << key.second;
        return std::nullopt;
    }
    const FieldVegetation &now = a->second.fields[f], &then = b->second.fields[f];
    const uint32_t i = plant - now.firstPlant;
    const double step = scene.sequence.timeStep;
    const PlantQuads p =
        plantQuads(atlas, scene.vegetation, scene.wind, now, i, plant, now.dynamicRecords[i], double(frame) * step);
    const PlantQuads q =
        plantQuads(atlas, scene.vegetation, scene.wind, then, i, plant, then.dynamicRecords[i], double(other) * step);
    moved = std::memcmp(&now.dynamicRecords[i], &then.dynamicRecords[i], sizeof(gpu::PlantDynamic)) != 0;
    const glm::dvec3 ray = from.ray(u + 0.5, v + 0.5), point = from.position + depth * ray;
    const glm::dvec3 dir = glm::normalize(ray);
    double best = INFINITY, b1 = 0.0, b2 = 0.0;
    uint32_t triangle = 0;
    for (uint32_t k = 0; k < PlantQuads::kTriangles; ++k) {
        double t, s1, s2;
        if (!hitTriangle(from.position, dir, corner(k, p.p0), corner(k, p.e1), corner(k, p.e2), t, s1, s2)) continue;
        const double miss = std::abs(t - glm::length(point - from.position));
        if (miss < best) best = miss, b1 = s1, b2 = s2, triangle = k;
    }
    if (best > 1e-3) return std::nullopt;
    const glm::dvec3 target =
        to.project(corner(triangle, q.p0) + b1 * corner(triangle, q.e1) + b2 * corner(triangle, q.e2));
    return glm::dvec2(target) - glm::dvec2(u + 0.5, v + 0.5);
}

// Frame f's flow to frame `other` (f + 1 forward, f - 1 backward), pixel by pixel: the ground's points reprojected
// into that frame's camera, the plants' moved from their state at f (`here`) to their state at `other` (`there`).
void checkFlow(const Scene& scene, const AtlasAlpha& atlas, const FrameImages& im, const std::vector<float>& flow,
               uint32_t frame, uint32_t other, const PlantStates& here, const PlantStates& there, FlowErrors& e) {
    ASSERT_EQ(flow.size(), size_t(kWidth) * kHeight * 4);
    const Camera from = cameraAt(scene, frame), to = cameraAt(scene, other);
    for (uint32_t v = 0; v < kHeight; ++v)
        for (uint32_t u = 0; u < kWidth; ++u) {
            const size_t i = size_t(v) * kWidth + u;
            const float* f = &flow[4 * i];
            const uint32_t semantic = im.labels[i] >> gpu::kInstanceBits;
            if (!std::isfinite(im.depth[i])) {
                ASSERT_EQ(f[3], 0.0f) << "a sky pixel has no flow: " << u << ", " << v;
                ++e.sky;
                continue;
            }
            ASSERT_EQ(f[3], 1.0f) << "frame " << frame << " pixel " << u << ", " << v;
            std::optional<glm::dvec2> expected;
            const bool ground =
                semantic == gpu::kSemanticGround || semantic == gpu::kSemanticTurf || semantic == gpu::kSemanticTrack;
            if (ground) {
                expected = glm::dvec2(to.project(from.position + double(im.depth[i]) * from.ray(u + 0.5, v + 0.5))) -
                           glm::dvec2(u + 0.5, v + 0.5);
            } else {
                ASSERT_TRUE((semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject) ||
                            semantic == gpu::kSemanticFelled)
                    << "class " << semantic;
                bool moved = false;
                expected = plantFlow(scene, atlas, from, to, u, v, im.depth[i], im.labels[i], im.tiles[i], frame, other,
                                     here, there, moved);
                if (!expected) continue;
                e.plantTiles.insert(im.tiles[i]);
                e.movedPlants += moved;
            }
            const double error = glm::length(*expected - glm::dvec2(f[0], f[1]));
            (ground ? e.ground : e.plants).push_back(error);
        }
}

} // namespace

// Each frame's forward and backward flow is exact in a world: the ground's is its depth reprojected with the next and
// the previous tick's cameras, the plants' (of every drawn tile, swaying in the wind and pressed by the rover) moves
// their points from this tick's state to that tick's, read back from the world's simulation. Frame 22 looks across
// a tile border; 62 is rendered after tile (0, 0) was evicted behind the camera between the ticks of its flow, 98
// after tile (3, 0) was made resident ahead of the rover.
TEST_F(GpuTest, WorldFlowIsTheDepthReprojectedAndThePlantsMovedByTheirStates) {
    const std::vector<uint32_t> frames{20, 21, 22, 60, 61, 62, 96, 97, 98};
    const FlowRun run = fly(*ctx, 9.0, frames, true);
    EXPECT_GT(run.stats.evicted, 0u) << "tile (0, 0) must be evicted behind the camera";
    EXPECT_TRUE(run.residentChanged.contains(Key(0, 0))) << "evicted between two rendered frames' ticks";
    EXPECT_TRUE(run.residentChanged.contains(Key(3, 0))) << "made resident between two rendered frames' ticks";
    const Scene scene = flowWorld(9.0);
    const SceneResources r = buildSceneResources(scene, true, 2);
    ASSERT_TRUE(r.atlas);
    const AtlasAlpha atlas(*r.atlas);
    FlowErrors forward, backward;
    for (uint32_t frame : {22u, 62u, 98u}) { // each with the two frames before: the states of f - 1, f and f + 1
        const FrameImages& im = run.frames.at(frame);
        const PlantStates &before = run.after.at(frame - 2), &here = run.after.at(frame - 1),
                          &next = run.after.at(frame);
        checkFlow(scene, atlas, im, im.flowForward, frame, frame + 1, here, next, forward);
        checkFlow(scene, atlas, im, im.flowBackward, frame, frame - 1, here, before, backward);
    }
    for (const auto& [name, e] :
         {std::pair<const char*, const FlowErrors&>{"forward", forward}, {"backward", backward}}) {
        std::printf("%s: %zu ground pixels, error median %.2e max %.2e px; %zu plant pixels (%llu moved by the rover) "
                    "of %zu tiles, error median %.2e, 99 %% %.2e px\n",
                    name, e.ground.size(), percentile(e.ground, 0.5), percentile(e.ground, 1.0), e.plants.size(),
                    (unsigned long long)e.movedPlants, e.plantTiles.size(), percentile(e.plants, 0.5),
                    percentile(e.plants, 0.99));
        EXPECT_GT(e.ground.size(), 500u) << name;
        EXPECT_GT(e.plants.size(), 500u) << name;
        EXPECT_GE(e.plantTiles.size(), 2u) << name << ": plants of both sides of the border";
        EXPECT_GT(e.movedPlants, 20u) << name << ": plants the rover presses or that spring back";
        EXPECT_LT(percentile(e.ground, 1.0), 2e-3) << name;
        EXPECT_LT(percentile(e.plants, 0.99), 2e-3) << name;
    }
}

// The same frames streamed (tiles evicted and made resident between the ticks of consecutive frames) and wholly
// resident are bitwise the same: colour, depth, labels, tiles and both flows. The resident run starts each run of
// frames one frame later (a shard's or a resumed run's first frame runs its own tick and keeps the state before it),
// the streamed run renders the frame before too (whose truth ran the next frame's tick).
TEST_F(GpuTest, WorldFlowIsBitwiseTheSameStreamedOrResident) {
    const FlowRun streamed = fly(*ctx, 9.0, {20, 21, 22, 60, 61, 62, 96, 97, 98}, false);
    const FlowRun resident = fly(*ctx, 200.0, {21, 22, 61, 62, 97, 98}, false);
    EXPECT_GT(streamed.stats.evicted, 0u);
    EXPECT_EQ(resident.stats.evicted, 0u);
    for (const auto& [f, b] : resident.frames) {
        const FrameImages& a = streamed.frames.at(f);
        EXPECT_EQ(a.rgbaHalf, b.rgbaHalf) << "colour, frame " << f;
        EXPECT_EQ(a.depth, b.depth) << "depth, frame " << f;
        EXPECT_EQ(a.labels, b.labels) << "labels, frame " << f;
        EXPECT_EQ(a.tiles, b.tiles) << "tiles, frame " << f;
        EXPECT_EQ(a.flowForward, b.flowForward) << "forward flow, frame " << f;
        EXPECT_EQ(a.flowBackward, b.flowBackward) << "backward flow, frame " << f;
    }
}
