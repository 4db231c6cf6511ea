// Near plants as blades (lod.near_blades): the GPU's blades against the CPU mirror, the near cards they replace left
// out, the ground truth and the colour pass drawing the same opaque fragments, and the coverage of the cards kept.
#include "expansion_fixtures.h"
#include "gpu_test.h"

#include "common/error.h"
#include "engine/pipeline_statistics.h"
#include "render/scene_renderer.h"
#include "render/vegetation_renderer.h"
#include "scene/scene.h"
#include "vegetation/atlas.h"
#include "vegetation/expansion_reference.h"

#include "shared/plant_blades.h"

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>
#include <map>

using namespace sward;
using sward::test::GpuTest;
using sward::test::readAll;
using sward::test::SceneSetup;

namespace {

constexpr uint32_t kWidth = 200, kHeight = 150;
constexpr uint32_t kBlades = 7;

// The default categories (ferns, grass, flowers), near plants out to 5 m, wind on.
nlohmann::json bladeFieldJson(uint32_t blades) {
    nlohmann::json json = nlohmann::json::parse(R"({
        "seed": 9,
        "terrain": {"size": 50, "spacing": 1, "amplitude": 2, "feature_size": 30},
        "camera": {"position": [10, 8, 0], "height_above_ground": 1.4,
                   "look_at": [30, 30, 0], "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "render": {"shadow_map_size": 256, "shadow_distance": 20},
        "lod": {"near": 5, "mid": 12, "far": 30, "band": 2}
    })");
    json["lod"]["near_blades"] = blades;
    return json;
}

} // namespace

TEST(Blades, SceneKeyDefaultsToCardsAndIsBounded) {
    EXPECT_EQ(parseScene(nlohmann::json::object(), "default").lod.nearBlades, 0u);
    EXPECT_EQ(parseScene(bladeFieldJson(kBlades), "blades").lod.nearBlades, kBlades);
    EXPECT_THROW(parseScene(bladeFieldJson(gpu::kMaxNearBlades + 1), "too many"), Error);
}

// Each blade index names a vertex of its own blade, and every segment's two triangles and the tip's one use the
// blade's vertices once at least.
TEST(Blades, IndexPatternCoversEachBladesVertices) {
    for (uint32_t blade = 0; blade < 3; ++blade) {
        std::vector<int> used(gpu::kBladeVertices, 0);
        for (uint32_t k = blade * gpu::kBladeIndices; k < (blade + 1) * gpu::kBladeIndices; ++k) {
            const uint32_t v = gpu::bladeIndex(k);
            ASSERT_EQ(v / gpu::kBladeVertices, blade);
            ++used[v % gpu::kBladeVertices];
        }
        for (uint32_t v = 0; v < gpu::kBladeVertices; ++v) EXPECT_GT(used[v], 0) << "vertex " << v;
    }
}

// The bake runs the blade draw's vertex math (plant_blades.glsl) on the GPU's own instances; the CPU mirror places
// the same points. The near cards of the grass plants are baked degenerate (the card draw leaves them out), the
// blades of the other categories too.
TEST_F(GpuTest, NearBladesMatchTheCpuReference) {
    SceneSetup s(bladeFieldJson(kBlades), "blade test");
    const Camera camera = s.camera(kWidth, kHeight);
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
    VegetationRenderer& vegetation = *renderer.vegetation();
    renderFrame(*ctx, renderer, camera, 0.7);
    const gpu::ExpansionStats stats = vegetation.readStats();
    ASSERT_GT(stats.instances.x, 20u);
    const auto plants = readAll<gpu::ExpandedPlant>(*ctx, vegetation.instances(), stats.instances.w);
    BakedPlants baked = vegetation.bake(0);
    const auto vertices = readAll<gpu::BakedVertex>(*ctx, baked.vertices, baked.vertexCount);
    vegetation.destroyBaked(baked);
    const uint32_t perPlant = kBlades * gpu::kBladeIndices;
    uint32_t bladesStart = 0;
    for (uint32_t lod = 0; lod < gpu::kLodCount; ++lod)
        bladesStart += stats.instances[int(lod)] * gpu::plantVertexCount(lod, 0);
    ASSERT_EQ(vertices.size(), bladesStart + stats.instances.x * perPlant);
    uint32_t grass = 0, other = 0;
    float bent = 0.0f;
    for (uint32_t i = 0; i < stats.instances.x; ++i) {
        const gpu::ExpandedPlant& plant = plants[i];
        const uint32_t category = plant.attributes & 3u;
        const glm::vec3 base(plant.positionHeight);
        const gpu::BakedVertex* blades = &vertices[bladesStart + i * perPlant];
        const gpu::BakedVertex* cards = &vertices[i * gpu::plantVertexCount(gpu::kLodNear, 0)];
        if (atlasPlantKindForCategory(s.scene.vegetation.categories[category].name) != AtlasPlantKind::Grass) {
            ++other;
            for (uint32_t k = 0; k < perPlant; ++k) ASSERT_EQ(glm::vec3(blades[k].positionFraction), base);
            continue;
        }
        ++grass;
        for (uint32_t k = 0; k < gpu::plantVertexCount(gpu::kLodNear, 0); ++k)
            ASSERT_EQ(glm::vec3(cards[k].positionFraction), base) << "the near cards of a plant drawn as blades";
        const uint32_t variant = ((plant.attributes >> 2) & 63u) % uint32_t(s.atlas.desc.rows[category].cells.size());
        const std::vector<glm::vec3> expected =
            referenceBladeVertices(plant, kBlades, s.atlas.desc.rows[category].cells[variant].aspect);
        ASSERT_EQ(expected.size(), perPlant);
        for (uint32_t k = 0; k < perPlant; ++k) {
            ASSERT_LT(glm::distance(glm::vec3(blades[k].positionFraction), expected[k]), 1e-4f)
                << "plant " << i << " vertex " << k;
            bent = std::max(bent, glm::length(glm::unpackHalf2x16(plant.tip)));
        }
        // Blades have width, unless thinned by the cross-fade to the mid LOD.
        if ((plant.fade & 0xffu) == 0) {
            EXPECT_GT(glm::distance(expected[0], expected[1]), 1e-4f);
        }
    }
    EXPECT_GT(grass, 20u);
    std::printf("near plants: %u grass as blades, %u others as cards\n", grass, other);
    EXPECT_GT(bent, 0.05f) << "the wind bends the blades";
}

// Blades are opaque: the truth pass and the colour pass (1x) shade the same fragments of them, so labels, depth and
// colour agree; and the blades cover about what the near cards did, from eye height.
TEST_F(GpuTest, NearBladesAreDrawnAlikeByEveryPassAndCoverWhatTheCardsDid) {
    auto plantPixels = [&](uint32_t blades) {
        SceneSetup s(bladeFieldJson(blades), "blade test");
        SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
        FrameImages frame = renderFrame(*ctx, renderer, s.camera(kWidth, kHeight), 0.7);
        size_t plants = 0;
        for (uint32_t label : frame.labels)
            plants += (label >> gpu::kInstanceBits) >= gpu::kSemanticVegetation &&
                      (label >> gpu::kInstanceBits) < gpu::kSemanticObject;
        return plants;
    };
    const size_t cards = plantPixels(0), blades = plantPixels(kBlades);
    std::printf("plant pixels: cards %zu, %u blades %zu\n", cards, kBlades, blades);
    EXPECT_GT(double(blades), 0.85 * double(cards));

    SceneSetup s(bladeFieldJson(kBlades), "blade test");
    const Camera camera = s.camera(kWidth, kHeight);
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
    VegetationRenderer& vegetation = *renderer.vegetation();
    RenderTarget main(*ctx, mainPassTargetDesc(camera.width, camera.height, 1));
    RenderTarget truth(*ctx, truthPassTargetDesc(camera.width, camera.height));
    const SceneRenderer::View view{&camera, &main, &truth};
    if (!ctx->device.supportsPipelineStatistics()) GTEST_SKIP() << "the device cannot count pipeline statistics";
    PipelineStatistics statistics(ctx->device, 4 * (gpu::kMaxShadowCascades + 2) + 1);
    ctx->submitter.immediate([&](VkCommandBuffer cmd) { renderer.recordExpansion(cmd, {&view, 1}, 0.0, 0); });
    ctx->submitter.immediate([&](VkCommandBuffer cmd) {
        statistics.reset(cmd);
        vegetation.setStatistics(&statistics);
        renderer.recordViews(cmd, {&view, 1}, 0.0, 0, nullptr, /* expand= */ false);
        vegetation.setStatistics(nullptr);
    });
    std::map<std::string, DrawStatistics> ranges;
    for (const auto& [name, figures] : statistics.read()) ranges[name] = figures;
    const DrawStatistics colour = ranges.at("main.blades"), drawn = ranges.at("truth.blades");
    ASSERT_GT(drawn.fragmentInvocations, 0u);
    EXPECT_EQ(colour.clippingPrimitives, drawn.clippingPrimitives);
    EXPECT_EQ(colour.fragmentInvocations, drawn.fragmentInvocations);
}
