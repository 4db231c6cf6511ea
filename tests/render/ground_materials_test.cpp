// Ground materials per vegetation category (issue 46): where a category with a ground_material of its own grows,
// the bare ground takes that preset in proportion to the category's grass-map value; a scene whose categories have
// none, or the terrain's own, reads no weights and draws exactly the terrain's material.
#include "gpu_test.h"

#include "common/half_float.h"
#include "io/image_files.h"
#include "render/scene_gpu.h"
#include "render/scene_renderer.h"
#include "scene/scene_resources.h"
#include "test_files.h"

#include <nlohmann/json.hpp>

#include <cstdio>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;

// A flat 40 m field seen straight down from 25 m, image up north: its grass map's west half grows category 0 (R),
// its east half category 1 (G), both so sparse (0.01 plants per m^2) that no turf covers the ground.
FrameImages topDown(Context& ctx, const nlohmann::json& categories) {
    const std::string map = tempDir("ground-materials") + "/halves.png";
    std::vector<uint8_t> texels(8 * 8 * 3, 0);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) texels[(y * 8 + x) * 3 + (x < 4 ? 0 : 1)] = 255;
    writePng8(map, 8, 8, 3, texels);
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 3,
        "terrain": {"size": 40, "spacing": 1, "amplitude": 0},
        "camera": {"position": [20, 20, 0], "height_above_ground": 25, "look_at": [20, 20.01, 0],
                   "look_at_height_above_ground": 0, "fov_y_deg": 60},
        "render": {"samples": 1, "shadow_map_size": 256}
    })");
    json["grass_map"] = map;
    json["vegetation"] = {{"field_size", 20}, {"categories", categories}};
    SceneResources resources = buildSceneResources(parseScene(json, "ground-materials.json"), true, 2);
    const Camera camera = sceneCamera(resources.scene, resources.terrain, kWidth, kHeight);
    SceneGpu gpu = createSceneGpu(ctx, resources, 1, SimulationMode::None);
    return renderFrame(ctx, *gpu.renderer, camera);
}

// Mean linear luminance of the pixels labelled bare ground in columns [x0, x1).
double groundLuminance(const FrameImages& frame, uint32_t x0, uint32_t x1) {
    double sum = 0.0;
    size_t count = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = x0; x < x1; ++x) {
            const size_t i = size_t(y) * kWidth + x;
            if ((frame.labels[i] >> gpu::kInstanceBits) != gpu::kSemanticGround) continue;
            const uint16_t* p = &frame.rgbaHalf[4 * i];
            sum += 0.2126 * halfBitsToFloat(p[0]) + 0.7152 * halfBitsToFloat(p[1]) + 0.0722 * halfBitsToFloat(p[2]);
            ++count;
        }
    EXPECT_GT(count, size_t(kHeight * (x1 - x0) / 2)) << "columns " << x0 << ".." << x1 << ": too little bare ground";
    return count ? sum / double(count) : 0.0;
}

} // namespace

TEST(GroundMaterialConstants, AreFlaggedOnlyWhenACategoryHasAMaterialOtherThanTheTerrains) {
    Scene scene;
    scene.terrain.material = gpu::kGroundMaterialGravel;
    EXPECT_EQ(groundMaterialConstants(scene), glm::uvec4(3u, 0u, 0x030303u, 0u)) << "none: the terrain's";
    scene.vegetation.categories[1].groundMaterial = int32_t(gpu::kGroundMaterialGravel);
    EXPECT_EQ(groundMaterialConstants(scene).y, 0u) << "the terrain's own material changes nothing";
    scene.vegetation.categories[2].groundMaterial = int32_t(gpu::kGroundMaterialMud);
    EXPECT_EQ(groundMaterialConstants(scene), glm::uvec4(3u, 1u, 0x020303u, 0u));
    scene.vegetation.categories[3].groundMaterial = int32_t(gpu::kGroundMaterialForestFloor);
    EXPECT_EQ(groundMaterialConstants(scene).z, 0x020303u) << "category 3 is not one of the scene's 3";
}

TEST_F(GpuTest, ACategorysGroundMaterialColoursTheBareGroundWhereItGrows) {
    const FrameImages halves = topDown(*ctx, nlohmann::json::parse(R"([{"density": 0.01, "ground_material": "mud"},
                                        {"density": 0.01, "ground_material": "dry_soil"}])"));
    // x = 20 m is the image's middle column; keep 20 px (about 2 m) clear of it either side.
    const double west = groundLuminance(halves, 0, kWidth / 2 - 20),
                 east = groundLuminance(halves, kWidth / 2 + 20, kWidth);
    std::printf("bare ground luminance: mud (west) %.4f, dry soil (east) %.4f\n", west, east);
    EXPECT_LT(west, 0.6 * east) << "mud is darker than dry soil";

    // The terrain's own material named on every category is no material of its own: the same picture, bit for bit.
    const FrameImages none = topDown(*ctx, nlohmann::json::parse(R"([{"density": 0.01}, {"density": 0.01}])"));
    const FrameImages soil = topDown(*ctx, nlohmann::json::parse(R"([{"density": 0.01, "ground_material": "soil"},
                                        {"density": 0.01, "ground_material": "soil"}])"));
    EXPECT_EQ(none.rgbaHalf, soil.rgbaHalf);
    EXPECT_NE(none.rgbaHalf, halves.rgbaHalf);
}
