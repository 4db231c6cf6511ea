// Scene objects and gusts in a world of several tiles (issue 51, scene/world_objects.h): a rover on a path across tile
// borders is drawn in colour and truth and presses the plants of every tile it reaches, gusts blow around the camera,
// and the frames are bitwise those of a world whose tiles all stay resident.
#include "gpu_test.h"

#include "interaction/state_file.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/rover_model.h"
#include "scene/scene_resources.h"
#include "scene/world_objects.h"
#include "shared/gpu_layout.h"

#include <set>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;

// 4 x 1 tiles of 20 m. A rover (2 m long: scale 2) drives east along y = 10 from x = 12 to 48 at 3 m/s, across the
// borders at x = 20 and 40, its chassis box pressing the plants; the camera follows 6 m behind and 4 m to the side,
// looking east. `loadRadius` 12 m streams (tile (0, 0) is evicted once both have left it and its plants have
// recovered, 30 ticks after the last contact); 400 m keeps every tile resident. Both draw out to 10 m. `gusts`: that
// many gusts over the world's 80 x 20 m.
Scene roverWorld(const std::string& dir, double loadRadius, uint32_t gusts) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 20, "spacing": 1, "amplitude": 1, "feature_size": 30, "octaves": 2},
        "vegetation": {"tile_size": 20, "field_size": 10},
        "interaction": {"recovery": {"rest_ticks": 30}},
        "world": {"tiles": [4, 1], "view_distance": 10, "memory_budget_mib": 256},
        "camera": {"path": {"points": [[6, 6], [80, 6]], "speed": 3, "height_above_ground": 2},
                   "look_ahead": 10, "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "objects": [{"name": "rover", "model": "rover.gltf", "scale": 2,
                     "path": {"points": [[12, 10], [48, 10]], "speed": 3},
                     "colliders": [{"node": "chassis", "shape": "box", "half_extents": [0.4, 0.55, 0.3],
                                    "offset": [0, 0, -0.15], "force": 2}]}],
        "render": {"shadow_map_size": 256, "shadow_distance": 10},
        "lod": {"near": 2, "mid": 4, "far": 7, "band": 2},
        "sequence": {"frames": 120, "time_step": 0.1}
    })");
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 2.0;
    if (gusts > 0) json["gusts"] = {{"count", gusts}, {"height", 0.5}};
    return parseScene(json, dir + "/scene.json");
}

// The planar depth at which pixel (u, v)'s centre ray first meets object 0's triangles, posed as worldColliders and
// the renderer pose it (on its objectGround): the CPU reference of the drawn rover (Moller-Trumbore in double).
double roverDepth(const SceneResources& r, const Camera& camera, double time, uint32_t u, uint32_t v) {
    const ObjectParams& object = r.scene.objects[0];
    const ObjectModel& model = r.models[0];
    const std::vector<glm::dmat4> nodes =
        objectNodeTransforms(object, model, objectGround(r.scene, object, model, time), time);
    const glm::dvec3 o = camera.position, d = camera.ray(u + 0.5, v + 0.5);
    double nearest = INFINITY;
    for (size_t n = 0; n < model.nodes.size(); ++n)
        for (const ModelPrimitive& prim : model.nodes[n].primitives)
            for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
                glm::dvec3 p[3];
                for (int k = 0; k < 3; ++k)
                    p[k] = glm::dvec3(nodes[n] * glm::dvec4(glm::dvec3(prim.positions[prim.indices[i + k]]), 1.0));
                const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0], h = glm::cross(d, e2);
                const double det = glm::dot(e1, h);
                if (std::abs(det) < 1e-12) continue;
                const glm::dvec3 s = o - p[0], q = glm::cross(s, e1);
                const double a = glm::dot(s, h) / det, b = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
                if (a >= 0.0 && b >= 0.0 && a + b <= 1.0 && t > 0.0) nearest = std::min(nearest, t);
            }
    return nearest;
}

struct Drive {
    std::vector<FrameImages> frames;
    uint64_t roverPixels = 0, roverPixelsOnReference = 0; // pixels labelled the rover; those within 1 mm of roverDepth
    WorldTileStats stats;
    uint64_t contacts = 0;
    std::set<std::pair<int32_t, int32_t>> touchedTiles; // (x, y) of the tiles with touched fields at the end
};

Drive drive(Context& ctx, const std::string& dir, double loadRadius, uint32_t gusts,
            const std::vector<uint32_t>& frames) {
    SceneResources r = buildSceneResources(roverWorld(dir, loadRadius, gusts), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_TRUE(gpu.worldSimulation != nullptr);
    EXPECT_TRUE(gpu.renderer->objects() != nullptr);
    OffscreenFrame target(ctx, kWidth, kHeight, 1);
    Drive run;
    for (uint32_t frame : frames) {
        RigCameras cameras;
        run.frames.push_back(renderSequenceFrame(gpu, target, r, kWidth, kHeight, frame, 0.0, std::nullopt, cameras));
        const FrameImages& im = run.frames.back();
        for (uint32_t i = 0; i < kWidth * kHeight; ++i)
            if (im.labels[i] == objectLabel(0)) {
                ++run.roverPixels;
                const double time = frame * r.scene.sequence.timeStep;
                run.roverPixelsOnReference +=
                    std::abs(roverDepth(r, cameras.left, time, i % kWidth, i / kWidth) - im.depth[i]) < 1e-3;
            }
    }
    run.stats = r.world->stats();
    run.contacts = gpu.worldSimulation->contacts();
    const std::string path = dir + "/state-" + std::to_string(int(loadRadius)) + ".swardws";
    gpu.worldSimulation->saveState(path);
    for (const TileInteractionState& tile : loadWorldState(path, r.scene.seed).tiles)
        run.touchedTiles.emplace(tile.coord.x, tile.coord.y);
    return run;
}

void expectBitwiseEqual(const Drive& streamed, const Drive& resident, const std::vector<uint32_t>& frames) {
    for (size_t f = 0; f < frames.size(); ++f) {
        EXPECT_EQ(streamed.frames[f].rgbaHalf, resident.frames[f].rgbaHalf) << "colour, frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].depth, resident.frames[f].depth) << "depth, frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].labels, resident.frames[f].labels) << "labels, frame " << frames[f];
        EXPECT_EQ(streamed.frames[f].tiles, resident.frames[f].tiles) << "tiles, frame " << frames[f];
    }
}

class WorldObjectsTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        dir = tempDir("world-objects");
        saveRoverGltf(dir + "/rover.gltf");
    }
    std::string dir;
};

} // namespace

// The rover is drawn with its label (no tile: an object belongs to none) in every frame, at the depth of a CPU ray cast
// of its posed triangles (176 of 177 pixels within 1 mm), presses the plants of the three tiles it crosses, and the
// frames are bitwise those of the resident world, though tile (0, 0) was evicted.
TEST_F(WorldObjectsTest, RoverAcrossTileBordersIsDrawnPressesBothSidesAndStreamsBitwise) {
    // Tick 27: the rover straddles x = 20; 70: x = 33; 115: x = 46, tile (0, 0) left behind.
    const std::vector<uint32_t> frames{27, 70, 115};
    const Drive streamed = drive(*ctx, dir, 12.0, 0, frames);
    const Drive resident = drive(*ctx, dir, 400.0, 0, frames);
    EXPECT_GT(streamed.stats.evicted, 0u) << "the drive must leave tile (0, 0) behind";
    EXPECT_EQ(resident.stats.evicted, 0u);
    EXPECT_GT(streamed.contacts, 100u);
    EXPECT_EQ(streamed.contacts, resident.contacts);
    expectBitwiseEqual(streamed, resident, frames);
    for (const auto& tile : {std::pair(0, 0), std::pair(1, 0), std::pair(2, 0)})
        EXPECT_TRUE(streamed.touchedTiles.contains(tile)) << "tile (" << tile.first << ", 0) has no pressed plant";
    EXPECT_EQ(streamed.touchedTiles, resident.touchedTiles);
    for (size_t f = 0; f < frames.size(); ++f) {
        const FrameImages& im = streamed.frames[f];
        uint32_t rover = 0;
        for (size_t i = 0; i < im.labels.size(); ++i)
            if (im.labels[i] == objectLabel(0)) {
                ++rover;
                EXPECT_EQ(im.tiles[i], 0u) << "an object's pixel names no tile";
            }
        EXPECT_GT(rover, 20u) << "the rover is seen in frame " << frames[f];
    }
    // Drawn where it stands: the truth depth of its pixels is the CPU ray cast's (edge pixels may graze another face).
    EXPECT_GE(double(streamed.roverPixelsOnReference), 0.95 * double(streamed.roverPixels))
        << streamed.roverPixelsOnReference << " of " << streamed.roverPixels;
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}

// Gusts blow around the camera (within view_distance): with them the streamed frames (tile (3, 0) never resident) are
// still bitwise those of the resident world, and they bend plants the rover alone does not.
TEST_F(WorldObjectsTest, GustsAroundTheCameraStreamBitwise) {
    const std::vector<uint32_t> frames{30, 60};
    const Drive streamed = drive(*ctx, dir, 12.0, 40, frames);
    const Drive resident = drive(*ctx, dir, 400.0, 40, frames);
    const Drive calm = drive(*ctx, dir, 12.0, 0, frames);
    EXPECT_LT(streamed.stats.generated, 4u);
    EXPECT_EQ(resident.stats.generated, 4u);
    EXPECT_EQ(streamed.contacts, resident.contacts);
    EXPECT_GT(streamed.contacts, calm.contacts) << "the gusts bend plants";
    expectBitwiseEqual(streamed, resident, frames);
    uint64_t changed = 0;
    for (size_t i = 0; i < streamed.frames[1].rgbaHalf.size(); ++i)
        changed += streamed.frames[1].rgbaHalf[i] != calm.frames[1].rgbaHalf[i];
    EXPECT_GT(changed, 0u) << "the gusts show";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}
