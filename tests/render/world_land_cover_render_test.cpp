// A world whose vegetation comes from a land cover (issue 51, part B): frames of a flight across tile borders are
// bitwise the same whether tiles come and go around the camera or all stay resident, the horizon ring's far cover
// taken from the land cover too.
#include "gpu_test.h"
#include "world_flight.h"

#include "common/optional_components.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <fstream>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;

// An ungeoreferenced 16 x 16 raster over 4 x 4 tiles of 40 m (10 m pixels, 4 per tile): stripes of grassland,
// shrubland, cropland and bare ground with a water pond, so borders between classes cross tile borders.
std::string writeCover(const std::string& dir) {
    const std::string path = dir + "/cover.asc";
    std::ofstream grid(path);
    grid << "ncols 16\nnrows 16\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    const int stripes[] = {30, 30, 20, 40, 30, 60, 20, 30};
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            const bool pond = x >= 6 && x < 9 && y >= 7 && y < 10;
            grid << (pond ? 80 : stripes[(x + y / 3) % 8]) << (x == 15 ? "\n" : " ");
        }
    return path;
}

// 4 x 4 tiles of 40 m; the camera flies diagonally across six of them, 3 m above the ground, looking ahead.
// `loadRadius` 35 m streams; 400 m keeps the whole world resident. Both draw out to 35 m, the horizon beyond.
Scene landCoverWorld(const std::string& cover, double loadRadius) {
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
    json["land_cover"] = {{"file", cover}, {"preset", "esa_worldcover"}, {"border", 12}};
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 10.0;
    json["world"]["memory_budget_mib"] = 512;
    return parseScene(json, "land-cover world");
}

using Flight = sward::test::WorldFlight;

Flight fly(Context& ctx, const std::string& cover, double loadRadius, uint32_t frames) {
    return sward::test::flyWorld(ctx, landCoverWorld(cover, loadRadius), kWidth, kHeight, frames);
}

} // namespace

TEST_F(GpuTest, WorldLandCoverFramesAreBitwiseTheSameStreamedOrResident) {
    if (!hasComponent(Component::Gdal)) GTEST_SKIP() << "this build of sward leaves out Gdal";
    constexpr uint32_t kFrames = 10; // 10 s at 12 m/s: 120 m, across the diagonal tiles (0,0) .. (2,2)
    const std::string cover = writeCover(sward::test::tempDir("world-land-cover"));
    const Flight streamed = fly(*ctx, cover, 35.0, kFrames);
    const Flight resident = fly(*ctx, cover, 400.0, kFrames);
    EXPECT_GT(streamed.evicted, 0u) << "the flight must leave tiles behind";
    EXPECT_EQ(resident.evicted, 0u);
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
    // 408 of 30,720 pixels at 64x48 (thin blades, bare and cropland stripes): the flight sees the land cover's plants.
    EXPECT_GT(plantPixels, uint64_t(kFrames) * kWidth * kHeight / 200) << "the flight sees plants";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}
