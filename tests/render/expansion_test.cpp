// GPU expansion against the CPU reference, LOD distribution, wind off, empty and full grass maps.
#include "expansion_fixtures.h"
#include "gpu_test.h"

#include "engine/pipeline_statistics.h"
#include "io/image_files.h"
#include "render/scene_renderer.h"
#include "render/vegetation_renderer.h"
#include "scene/scene.h"
#include "vegetation/atlas_cutout.h"
#include "vegetation/expansion_reference.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

using namespace sward;
using sward::test::GpuTest;
using sward::test::readAll;
using sward::test::SceneSetup;
using sward::test::tempDir;

namespace {

constexpr uint32_t kWidth = 200, kHeight = 150;

nlohmann::json smallFieldJson() {
    return nlohmann::json::parse(R"({
        "seed": 9,
        "terrain": {"size": 50, "spacing": 1, "amplitude": 2, "feature_size": 30},
        "camera": {"position": [10, 8, 0], "height_above_ground": 1.4,
                   "look_at": [30, 30, 0], "look_at_height_above_ground": 0, "fov_y_deg": 70},
        "render": {"shadow_map_size": 256, "shadow_distance": 20},
        "lod": {"near": 5, "mid": 12, "far": 30, "band": 2}
    })");
}

// Fraction of terrain pixels that vegetation covers (truth depth in front of the bare terrain).
double coverage(const FrameImages& bare, const FrameImages& grass) {
    size_t ground = 0, covered = 0;
    for (size_t i = 0; i < bare.depth.size(); ++i) {
        if (!std::isfinite(bare.depth[i])) continue;
        ++ground;
        covered += grass.depth[i] < bare.depth[i] - 0.01f;
    }
    return ground ? double(covered) / double(ground) : 0.0;
}

// Expands on the GPU and checks instances and baked vertices (whole quads, or cut-out fans) against the CPU reference.
void expectExpansionMatchesTheCpuReference(Context* ctx, uint32_t cutoutCorners) {
    SceneSetup s(smallFieldJson(), "expansion test");
    Camera camera = s.camera(kWidth, kHeight);
    const double time = 0.7;
    ReferenceExpansion reference = referenceExpand(s.tile, s.scene.vegetation, s.scene.lod, s.scene.wind, camera, time,
                                                   {cardCover(s.atlas), meanAspects(s.atlas.desc)});
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
    VegetationRenderer& vegetation = *renderer.vegetation();
    vegetation.setCutout(cutoutCorners, s.atlas);
    renderFrame(*ctx, renderer, camera, time);
    gpu::ExpansionStats stats = vegetation.readStats();
    const std::vector<CutoutPolygon> polygons = atlasCutouts(s.atlas, cutoutCorners ? cutoutCorners : 4);

    // The expansion lays clusters out front to back; here that is not their index order, so the instance-by-instance
    // comparison below checks the order too.
    std::vector<uint32_t> order;
    frontToBack(clusterBoxes(s.tile), glm::vec3(camera.position), order);
    EXPECT_FALSE(std::is_sorted(order.begin(), order.end()));
    ASSERT_GT(reference.lods[0].size(), 0u);
    ASSERT_GT(reference.lods[1].size(), 0u);
    ASSERT_GT(reference.lods[2].size(), 0u);
    EXPECT_EQ(stats.info.x, reference.visibleClusters);
    EXPECT_EQ(stats.info.z, reference.plantsConsidered);
    for (uint32_t lod = 0; lod < 3; ++lod)
        EXPECT_EQ(stats.instances[int(lod)], reference.lods[lod].size()) << "LOD " << lod;

    auto gpuPlants = readAll<gpu::ExpandedPlant>(*ctx, vegetation.instances(), stats.instances.w);
    BakedPlants baked = vegetation.bake(0);
    auto vertices = readAll<gpu::BakedVertex>(*ctx, baked.vertices, baked.vertexCount);
    vegetation.destroyBaked(baked);

    size_t index = 0, vertex = 0, checked = 0;
    for (uint32_t lod = 0; lod < 3; ++lod) {
        for (const gpu::ExpandedPlant& expected : reference.lods[lod]) {
            const gpu::ExpandedPlant& actual = gpuPlants[index++];
            ASSERT_LT(glm::distance(glm::vec3(actual.positionHeight), glm::vec3(expected.positionHeight)), 1e-4f);
            ASSERT_NEAR(actual.positionHeight.w, expected.positionHeight.w, 1e-5f);
            ASSERT_EQ(actual.up, expected.up);
            ASSERT_EQ(actual.attributes, expected.attributes);
            ASSERT_EQ(actual.fade & 0xffffff00u, expected.fade & 0xffffff00u); // merging width, state, cut
            ASSERT_NEAR(double(actual.fade & 0xffu), double(expected.fade & 0xffu), 1.0);
            // Vertices from the GPU's own instance (so only the vertex math is compared here).
            uint32_t category = actual.attributes & 3u;
            uint32_t variant = ((actual.attributes >> 2) & 63u) % uint32_t(s.atlas.desc.rows[category].cells.size());
            const AtlasCell& cell = s.atlas.desc.rows[category].cells[variant];
            auto corners = referencePlantVertices(
                actual, lod, glm::vec3(camera.position), glm::vec3(cell.baseU, cell.baseV, cell.aspect),
                &polygons[category * s.atlas.desc.maxColumns() + variant], cutoutCorners);
            ASSERT_EQ(corners.size(), gpu::plantVertexCount(lod, cutoutCorners));
            for (const glm::vec3& p : corners) {
                ASSERT_LT(glm::distance(glm::vec3(vertices[vertex].positionFraction), p), 1e-4f) << "vertex " << vertex;
                ++vertex;
            }
            ++checked;
        }
    }
    EXPECT_EQ(vertex, vertices.size());
    EXPECT_GT(checked, 100u);
}

} // namespace

TEST_F(GpuTest, ExpansionMatchesTheCpuReference) {
    expectExpansionMatchesTheCpuReference(ctx.get(), 0);
}

TEST_F(GpuTest, CutoutExpansionMatchesTheCpuReferenceForFourAndEightCorners) {
    expectExpansionMatchesTheCpuReference(ctx.get(), 4);
    expectExpansionMatchesTheCpuReference(ctx.get(), 8);
}

// Every pass draws plants indexed, each quad's corners once (gpu::plantIndex). The indexed draws rasterise the
// triangles of the unindexed fan (the bake's static vertices, drawn vertex by vertex), and the colour and truth
// passes draw the same ones: at 1x the same fragments, whole quads and cut-out fans alike.
TEST_F(GpuTest, IndexedPlantDrawsRasteriseTheTrianglesOfTheUnindexedDraw) {
    if (!ctx->device.supportsPipelineStatistics()) GTEST_SKIP() << "the device cannot count pipeline statistics";
    SceneSetup s(smallFieldJson(), "expansion test");
    const Camera camera = s.camera(kWidth, kHeight);
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
    VegetationRenderer& vegetation = *renderer.vegetation();
    RenderTarget main(*ctx, mainPassTargetDesc(camera.width, camera.height, 1));
    RenderTarget truth(*ctx, truthPassTargetDesc(camera.width, camera.height));
    const SceneRenderer::View view{&camera, &main, &truth};
    const bool llvmpipe = ctx->device.name().find("llvmpipe") != std::string::npos;
    for (uint32_t corners : {0u, 6u}) {
        SCOPED_TRACE(std::to_string(corners) + " cut-out corners");
        vegetation.setCutout(corners, s.atlas);
        PipelineStatistics statistics(ctx->device, 3 * (gpu::kMaxShadowCascades + 2) + 1);
        // lavapipe cannot count statistics in a command buffer that also dispatches compute: expansion first.
        ctx->submitter.immediate([&](VkCommandBuffer cmd) { renderer.recordExpansion(cmd, {&view, 1}, 0.0, 0); });
        ctx->submitter.immediate([&](VkCommandBuffer cmd) {
            statistics.reset(cmd);
            vegetation.setStatistics(&statistics);
            renderer.recordViews(cmd, {&view, 1}, 0.0, 0, nullptr, /* expand= */ false);
            vegetation.setStatistics(nullptr);
        });
        BakedPlants baked = vegetation.bake(0);
        ctx->submitter.immediate([&](VkCommandBuffer cmd) {
            vegetation.setStatistics(&statistics);
            renderer.recordMainOnly(cmd, main, camera, 0.0, 0, nullptr, &baked);
            vegetation.setStatistics(nullptr);
        });
        vegetation.destroyBaked(baked);
        std::map<std::string, DrawStatistics> ranges;
        for (const auto& [name, figures] : statistics.read()) ranges[name] = figures;
        DrawStatistics indexed{};
        for (const char* lod : {".near", ".mid", ".far"}) {
            SCOPED_TRACE(lod);
            const DrawStatistics colour = ranges.at(std::string("main") + lod),
                                 drawn = ranges.at(std::string("truth") + lod);
            ASSERT_GT(drawn.inputAssemblyPrimitives, 0u);
            EXPECT_EQ(colour.inputAssemblyPrimitives, drawn.inputAssemblyPrimitives);
            EXPECT_EQ(colour.clippingPrimitives, drawn.clippingPrimitives);
            EXPECT_EQ(colour.fragmentInvocations, drawn.fragmentInvocations);
            EXPECT_EQ(colour.vertexInvocations, drawn.vertexInvocations);
            // lavapipe shades each distinct index of an instance once: 4 vertices a whole quad (2 triangles), n a
            // cut-out fan of n - 2.
            const uint64_t perQuad = corners && std::string(lod) != ".far" ? corners : 4u;
            if (llvmpipe) {
                EXPECT_EQ(colour.vertexInvocations * (perQuad - 2), colour.inputAssemblyPrimitives * perQuad);
            }
            indexed.inputAssemblyPrimitives += colour.inputAssemblyPrimitives;
            indexed.clippingPrimitives += colour.clippingPrimitives;
            indexed.fragmentInvocations += colour.fragmentInvocations;
        }
        const DrawStatistics unindexed = ranges.at("main.static");
        EXPECT_EQ(unindexed.inputAssemblyPrimitives, indexed.inputAssemblyPrimitives);
        EXPECT_EQ(unindexed.vertexInvocations, 3 * unindexed.inputAssemblyPrimitives);
        EXPECT_EQ(unindexed.clippingPrimitives, indexed.clippingPrimitives);
        EXPECT_EQ(unindexed.fragmentInvocations, indexed.fragmentInvocations);
    }
}

TEST_F(GpuTest, LodShiftsFromNearToFarAsTheCameraRecedes) {
    SceneSetup s(smallFieldJson(), "expansion test");
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, &s.tile, &s.atlas);
    glm::dvec3 target(25.0, 25.0, s.terrain.height({25.0f, 25.0f}));
    double previousNearShare = 2.0, previousFarShare = -1.0;
    for (double back : {2.0, 8.0, 18.0}) {
        glm::dvec3 eye = target + glm::dvec3(-back, -back, 2.0 + back * 0.5);
        Camera camera = Camera::lookAt(eye, target, {0, 0, 1}, 60.0, 64, 48);
        renderFrame(*ctx, renderer, camera);
        gpu::ExpansionStats stats = renderer.vegetation()->readStats();
        ASSERT_GT(stats.instances.w, 0u);
        double nearShare = double(stats.instances.x) / stats.instances.w;
        double farShare = double(stats.instances.z) / stats.instances.w;
        EXPECT_LT(nearShare, previousNearShare) << "camera " << back << " m back";
        EXPECT_GT(farShare, previousFarShare) << "camera " << back << " m back";
        previousNearShare = nearShare;
        previousFarShare = farShare;
    }
}

TEST_F(GpuTest, WithoutWindTheImageIsStaticOverTime) {
    nlohmann::json json = smallFieldJson();
    json["wind"] = {{"strength", 0}, {"gust_strength", 0}, {"flutter", 0}};
    SceneSetup s(json, "expansion test");
    SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_4_BIT, &s.tile, &s.atlas);
    FrameImages a = renderFrame(*ctx, renderer, s.camera(kWidth, kHeight), 0.0);
    FrameImages b = renderFrame(*ctx, renderer, s.camera(kWidth, kHeight), 3.3);
    EXPECT_EQ(a.rgbaHalf, b.rgbaHalf);
    EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * 4));
}

TEST_F(GpuTest, EmptyGrassMapDrawsNoGrassAndFullMapCoversTheGroundFromAbove) {
    std::string dir = tempDir("grassmaps");
    std::vector<uint8_t> empty(8 * 8 * 3, 0), full(8 * 8 * 3, 0);
    for (size_t i = 1; i < full.size(); i += 3) full[i] = 255; // G = grass at full density
    writePng8(dir + "/empty.png", 8, 8, 3, empty);
    writePng8(dir + "/full.png", 8, 8, 3, full);

    // Top-down view from 6 m over the middle of the field.
    nlohmann::json json = smallFieldJson();
    json["camera"] = {{"position", {25, 25, 0}},
                      {"height_above_ground", 4},
                      {"look_at", {25, 25.01, 0}},
                      {"look_at_height_above_ground", 0},
                      {"fov_y_deg", 50}};
    auto render = [&](const std::string& map, bool vegetation, float grassDensity) {
        nlohmann::json j = json;
        j["grass_map"] = map;
        j["vegetation"] = {{"categories", {nlohmann::json::object(), {{"density", grassDensity}}}}};
        SceneSetup s(j, "expansion test");
        SceneRenderer renderer(*ctx, s.scene, s.terrain, VK_SAMPLE_COUNT_1_BIT, vegetation ? &s.tile : nullptr,
                               vegetation ? &s.atlas : nullptr);
        return renderFrame(*ctx, renderer, s.camera(kWidth, kHeight));
    };
    FrameImages bare = render(dir + "/empty.png", false, 16.0f);
    FrameImages none = render(dir + "/empty.png", true, 16.0f);
    EXPECT_EQ(coverage(bare, none), 0.0) << "an empty map must not draw a single plant pixel";
    EXPECT_EQ(0, std::memcmp(bare.depth.data(), none.depth.data(), bare.depth.size() * 4));
    // Thresholds, seen from 4 m straight above (near LOD): plant geometry (not the turf-coloured terrain)
    // covers >= 30% of the ground at the default 16 grass clumps per m^2 and >= 70% at 48 per m^2.
    double defaultDensity = coverage(bare, render(dir + "/full.png", true, 16.0f));
    double dense = coverage(bare, render(dir + "/full.png", true, 48.0f));
    EXPECT_GE(defaultDensity, 0.30);
    EXPECT_GE(dense, 0.70);
    EXPECT_GT(dense, defaultDensity);
    std::printf("top-down grass coverage: %.3f at 16/m^2, %.3f at 48/m^2\n", defaultDensity, dense);
}
