// Drawing a GIS world (issue 51, part A): a world whose ground is a DEM GeoTIFF (written here with GDAL), cut into
// tiles window by window. Frames of a flight across tile borders are bitwise the same whether the tiles come and go
// around the camera (streamed) or all stay resident.
#include "gpu_test.h"

#include "dem_files.h"
#include "test_files.h"
#include "world_flight.h"

#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <cmath>

using namespace sward;
using namespace sward::test;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;

// 81 x 61 samples of 1 m: 4 x 3 tiles of 20 m, valleys of a few metres (rows from the north).
const std::string& gisDem() {
    static const std::string path = [] {
        const std::string p = (tempDir() / "gis-world-dem.tif").string();
        writeDem(p, {.columns = 81, .rows = 61, .height = [](uint32_t c, uint32_t r) {
                         return 30.0 + 3.0 * std::sin(0.15 * c) * std::cos(0.11 * r) + 0.05 * c - 0.04 * r;
                     }});
        return p;
    }();
    return path;
}

// The camera flies diagonally across the borders x = 20, 40 and y = 20, 40, 2 m above the DEM. `loadRadius` 18 m
// streams; 400 m keeps the whole world resident. Both draw out to 18 m.
Scene gisWorld(double loadRadius) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 11,
        "vegetation": {"tile_size": 20, "field_size": 10, "density_multiplier": 0.3},
        "world": {"view_distance": 18},
        "camera": {"path": {"points": [[6, 5], [76, 56]], "speed": 10, "height_above_ground": 2},
                   "look_ahead": 8, "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "render": {"shadow_map_size": 256, "shadow_distance": 15},
        "lod": {"near": 3, "mid": 6, "far": 14, "band": 2}
    })");
    json["terrain"]["heightmap"]["file"] = gisDem();
    json["world"]["load_radius"] = loadRadius;
    json["world"]["evict_radius"] = loadRadius + 10.0;
    json["world"]["memory_budget_mib"] = 256;
    return parseScene(json, "gis world");
}

using Flight = sward::test::WorldFlight;

Flight fly(Context& ctx, double loadRadius, uint32_t frames) {
    return sward::test::flyWorld(ctx, gisWorld(loadRadius), kWidth, kHeight, frames);
}

} // namespace

TEST_F(GpuTest, GisWorldFramesAreBitwiseTheSameStreamedOrResident) {
    constexpr uint32_t kFrames = 6; // 50 m along the diagonal: the borders x = 20, 40 and y = 20 crossed
    const Flight streamed = fly(*ctx, 18.0, kFrames);
    const Flight resident = fly(*ctx, 400.0, kFrames);
    EXPECT_GT(streamed.evicted, 0u) << "the flight must leave tiles behind";
    EXPECT_EQ(resident.mostTilesDrawn, 12u);
    EXPECT_LT(streamed.mostTilesDrawn, 12u);
    uint64_t groundPixels = 0, plantPixels = 0;
    for (uint32_t f = 0; f < kFrames; ++f) {
        const FrameImages& a = streamed.frames[f];
        const FrameImages& b = resident.frames[f];
        EXPECT_EQ(a.rgbaHalf, b.rgbaHalf) << "left colour, frame " << f;
        EXPECT_EQ(a.rightRgbaHalf, b.rightRgbaHalf) << "right colour, frame " << f;
        EXPECT_EQ(a.depth, b.depth) << "depth, frame " << f;
        EXPECT_EQ(a.labels, b.labels) << "labels, frame " << f;
        for (uint32_t label : a.labels) {
            const uint32_t semantic = label >> gpu::kInstanceBits;
            groundPixels += semantic == gpu::kSemanticGround;
            plantPixels += semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject;
        }
    }
    EXPECT_GT(groundPixels + plantPixels, uint64_t(kFrames) * kWidth * kHeight / 4) << "the flight sees the DEM";
    EXPECT_GT(plantPixels, 0u) << "and grass on it";
    EXPECT_EQ(ctx->device.validationMessageCount(), 0u);
}
