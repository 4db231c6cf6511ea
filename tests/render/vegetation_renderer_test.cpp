// Vegetation expansion and rendering on the GPU: LOD choice, culling, wind, determinism, ground truth.
#include "gpu_test.h"

#include "common/half_float.h"
#include "render/scene_renderer.h"
#include "render/vegetation_renderer.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"
#include "vegetation/records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 240, kHeight = 160;

Scene smallMeadow() {
    return parseScene(nlohmann::json::parse(R"({
        "seed": 5,
        "terrain": {"size": 100, "spacing": 2, "amplitude": 4, "feature_size": 60},
        "camera": {"position": [20, 20, 0], "height_above_ground": 1.5,
                   "look_at": [50, 45, 0], "look_at_height_above_ground": 0, "fov_y_deg": 60},
        "render": {"shadow_map_size": 512, "shadow_distance": 30},
        "lod": {"near": 6, "mid": 15, "far": 45, "band": 2},
        "vegetation": {"tile_size": 100}
    })"),
                      "small meadow");
}

class VegetationTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        tile = buildVegetation(scene, terrain, 2);
        atlas = buildAtlas(scene);
    }
    std::unique_ptr<SceneRenderer> renderer(bool withVegetation, uint32_t samples = 4) {
        return std::make_unique<SceneRenderer>(*ctx, scene, terrain,
                                               samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                                               withVegetation ? &tile : nullptr, withVegetation ? &atlas : nullptr);
    }
    std::vector<gpu::ExpandedPlant> readInstances(VegetationRenderer& vegetation, uint32_t count) {
        std::vector<uint8_t> bytes = readBuffer(*ctx, vegetation.instances(), 0, uint64_t(count) * sizeof(gpu::ExpandedPlant));
        std::vector<gpu::ExpandedPlant> instances(count);
        std::memcpy(instances.data(), bytes.data(), bytes.size());
        return instances;
    }

    void expectPlantNormalsAgreeWithTheDepthImage(uint32_t blades);

    Scene scene = smallMeadow();
    Ground terrain = buildTerrain(scene);
    Camera camera = sceneCamera(scene, terrain, kWidth, kHeight);
    VegetationTile tile;
    Atlas atlas;
};

} // namespace

TEST_F(VegetationTest, PlantsStandInFrontOfTheTerrainInColourAndTruth) {
    FrameImages bare = renderFrame(*ctx, *renderer(false), camera);
    FrameImages grass = renderFrame(*ctx, *renderer(true), camera);
    size_t occluded = 0, ground = 0;
    for (size_t i = 0; i < bare.depth.size(); ++i) {
        if (!std::isfinite(bare.depth[i])) continue;
        ++ground;
        ASSERT_TRUE(std::isfinite(grass.depth[i])) << "a plant pixel in front of terrain cannot be sky";
        EXPECT_LE(grass.depth[i], bare.depth[i] + 1e-4f) << "vegetation never lies behind the ground it stands on";
        if (grass.depth[i] < bare.depth[i] - 0.01f) ++occluded;
    }
    ASSERT_GT(ground, bare.depth.size() / 3);
    EXPECT_GT(occluded, ground / 3) << "plants should cover much of the ground near the camera";
    EXPECT_NE(bare.rgbaHalf, grass.rgbaHalf);
}

namespace {

// Mean luminance of the colour at the pixels `where` picks.
double meanLuminance(const FrameImages& frame, const std::vector<size_t>& where) {
    double sum = 0.0;
    for (size_t i : where) {
        const uint16_t* c = &frame.rgbaHalf[4 * i];
        sum += 0.2126 * halfBitsToFloat(c[0]) + 0.7152 * halfBitsToFloat(c[1]) + 0.0722 * halfBitsToFloat(c[2]);
    }
    return sum / double(std::max<size_t>(where.size(), 1));
}

} // namespace

// Plants cast sun shadows: the shadow pass reads their alpha at its cascade's atlas level (shadowAtlasLevel). The
// ground seen between the plants, away from any plant's edge (its 3 x 3 neighbourhood all ground, so no blend of
// plant and ground at 4x), is darker than the same pixels of the bare terrain: 0.904 of it (0.929 with the trilinear
// lookup at each fragment's level this replaced, 0.882 at level 0). Without plant shadows (the shadow pass's fetch
// reading a level the atlas lacks, tried) it is 1.039.
TEST_F(VegetationTest, PlantsShadeTheGroundSeenBetweenThem) {
    FrameImages bare = renderFrame(*ctx, *renderer(false), camera);
    FrameImages grass = renderFrame(*ctx, *renderer(true), camera);
    auto ground = [&](uint32_t x, uint32_t y) {
        return (grass.labels[size_t(y) * kWidth + x] >> gpu::kInstanceBits) == gpu::kSemanticGround;
    };
    std::vector<size_t> between;
    for (uint32_t y = 1; y + 1 < kHeight; ++y)
        for (uint32_t x = 1; x + 1 < kWidth; ++x) {
            bool open = true;
            for (uint32_t v = y - 1; v <= y + 1; ++v)
                for (uint32_t u = x - 1; u <= x + 1; ++u) open = open && ground(u, v);
            if (open) between.push_back(size_t(y) * kWidth + x);
        }
    const double shaded = meanLuminance(grass, between), lit = meanLuminance(bare, between);
    std::printf("ground between the plants: %zu pixels, luminance %.4f against %.4f bare (%.3f)\n", between.size(),
                shaded, lit, shaded / lit);
    ASSERT_GT(between.size(), 200u);
    EXPECT_LT(shaded, 0.95 * lit);
}

namespace {

// The camera-frame point of pixel (x, y) at planar depth d (pixel centres at +0.5, camera.h).
glm::dvec3 backProject(const Camera& camera, uint32_t x, uint32_t y, double d) {
    return {(x + 0.5 - camera.cx) / camera.fx * d, (y + 0.5 - camera.cy) / camera.fy * d, d};
}

// The plane through the 3x3 neighbourhood of (x, y): its unit normal from central differences, and the largest
// distance of the nine points from that plane over the neighbourhood's size (0 for coplanar points).
std::pair<glm::dvec3, double> neighbourhoodPlane(const Camera& camera, const FrameImages& frame, uint32_t x,
                                                 uint32_t y) {
    auto point = [&](uint32_t u, uint32_t v) {
        return backProject(camera, u, v, frame.depth[size_t(v) * frame.width + u]);
    };
    const glm::dvec3 centre = point(x, y);
    const glm::dvec3 across = point(x + 1, y) - point(x - 1, y), down = point(x, y + 1) - point(x, y - 1);
    const glm::dvec3 n = glm::normalize(glm::cross(across, down));
    double residual = 0.0;
    for (uint32_t v = y - 1; v <= y + 1; ++v)
        for (uint32_t u = x - 1; u <= x + 1; ++u)
            residual = std::max(residual, std::abs(glm::dot(n, point(u, v) - centre)));
    return {n, residual / std::max(glm::length(across), glm::length(down))};
}

} // namespace

// Plants are alpha-tested cards: every plant pixel's normal is unit, faces the camera and is the plane the depth
// image shows wherever a 3x3 neighbourhood of one plant is planar.
// The truth normals of the plants (cards, or with `blades` lod.near_blades the near grass's blades) are unit, face the
// camera and are the plane the depth image shows around every pixel whose neighbourhood is one flat plant part.
void VegetationTest::expectPlantNormalsAgreeWithTheDepthImage(uint32_t blades) {
    scene.lod.nearBlades = blades;
    // Twice the fixture's resolution: more blades are several pixels wide.
    const uint32_t width = 2 * kWidth, height = 2 * kHeight;
    const Camera detailed = sceneCamera(scene, terrain, width, height);
    const FrameImages frame = renderFrame(*ctx, *renderer(true, 1), detailed, 1.0);
    ASSERT_EQ(frame.normals.size(), frame.depth.size() * 3);
    uint32_t plants = 0, planar = 0;
    double worst = 0.0;
    for (uint32_t y = 1; y + 1 < height; ++y)
        for (uint32_t x = 1; x + 1 < width; ++x) {
            const size_t i = size_t(y) * width + x;
            const uint32_t semantic = frame.labels[i] >> gpu::kInstanceBits;
            if (semantic < gpu::kSemanticVegetation || semantic == gpu::kSemanticObject) continue;
            ++plants;
            const glm::dvec3 n(frame.normals[3 * i], frame.normals[3 * i + 1], frame.normals[3 * i + 2]);
            ASSERT_NEAR(glm::length(n), 1.0, 1e-5) << "(" << x << "," << y << ")";
            ASSERT_LT(glm::dot(n, backProject(detailed, x, y, 1.0)), 0.0)
                << "faces the camera at (" << x << "," << y << ")";
            bool onePlant = true;
            for (uint32_t v = y - 1; v <= y + 1; ++v)
                for (uint32_t u = x - 1; u <= x + 1; ++u)
                    onePlant = onePlant && frame.labels[size_t(v) * width + u] == frame.labels[i];
            if (!onePlant) continue;
            auto [fitted, residual] = neighbourhoodPlane(detailed, frame, x, y);
            if (residual > 1e-4) continue; // two cards or blades of one plant, or one seen edge-on
            ++planar;
            const double angle = std::acos(std::min(1.0, std::abs(glm::dot(fitted, n))));
            worst = std::max(worst, angle);
            EXPECT_LT(angle, 1e-3) << "(" << x << "," << y << ") depth-plane vs written normal";
        }
    std::printf("plant pixels %u, planar neighbourhoods %u, worst angle %.3g rad\n", plants, planar, worst);
    EXPECT_GT(plants, width * height / 4);
    // A blade is a few pixels wide: fewer 3 x 3 neighbourhoods lie on one of its segments than on a card.
    EXPECT_GT(planar, blades ? 1200u : 2000u) << "too few planar plant neighbourhoods to test";
}

TEST_F(VegetationTest, PlantNormalsAreUnitFaceTheCameraAndAgreeWithTheDepthImage) {
    expectPlantNormalsAgreeWithTheDepthImage(0);
}

TEST_F(VegetationTest, BladeNormalsAreUnitFaceTheCameraAndAgreeWithTheDepthImage) {
    expectPlantNormalsAgreeWithTheDepthImage(8);
}

TEST_F(VegetationTest, BladesAtTheSameTimeAreBitwiseIdenticalAndWindMovesThem) {
    scene.lod.nearBlades = 8;
    auto r = renderer(true);
    FrameImages a = renderFrame(*ctx, *r, camera, 1.0);
    FrameImages b = renderFrame(*ctx, *r, camera, 1.0);
    FrameImages c = renderFrame(*ctx, *r, camera, 2.5);
    EXPECT_EQ(a.rgbaHalf, b.rgbaHalf);
    EXPECT_EQ(a.labels, b.labels);
    EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * 4));
    EXPECT_EQ(0, std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * 4));
    EXPECT_NE(0, std::memcmp(a.depth.data(), c.depth.data(), a.depth.size() * 4)) << "truth follows the wind";
}

TEST_F(VegetationTest, SameTimeIsBitwiseIdenticalAndWindMovesPlants) {
    auto r = renderer(true);
    FrameImages a = renderFrame(*ctx, *r, camera, 1.0);
    FrameImages b = renderFrame(*ctx, *r, camera, 1.0);
    FrameImages c = renderFrame(*ctx, *r, camera, 2.5);
    EXPECT_EQ(a.rgbaHalf, b.rgbaHalf);
    EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * 4));
    EXPECT_NE(a.rgbaHalf, c.rgbaHalf) << "wind is a function of simulation time";
    EXPECT_NE(0, std::memcmp(a.depth.data(), c.depth.data(), a.depth.size() * 4)) << "truth follows the wind";
}

TEST_F(VegetationTest, LodFollowsDistanceWithComplementaryCrossFadeCopies) {
    auto r = renderer(true);
    renderFrame(*ctx, *r, camera);
    VegetationRenderer& vegetation = *r->vegetation();
    gpu::ExpansionStats stats = vegetation.readStats();
    ASSERT_GT(stats.instances.x, 0u);
    ASSERT_GT(stats.instances.y, 0u);
    ASSERT_GT(stats.instances.z, 0u);
    EXPECT_EQ(stats.info.y, 0u) << "no instance may be dropped for lack of capacity here";
    std::vector<gpu::ExpandedPlant> instances = readInstances(vegetation, stats.instances.w);

    const float half = 0.5f * scene.lod.band;
    const float edges[4] = {0.0f, scene.lod.nearToMid, scene.lod.midToFar, scene.lod.farLimit};
    uint32_t begin = 0, upperCopies = 0, banded = 0;
    for (uint32_t lod = 0; lod < 3; ++lod) {
        uint32_t end = begin + stats.instances[int(lod)];
        for (uint32_t i = begin; i < end; ++i) {
            const gpu::ExpandedPlant& p = instances[i];
            float d = float(glm::distance(glm::dvec3(glm::vec3(p.positionHeight)), camera.position));
            ASSERT_GE(d, edges[lod] - half - 1e-3f) << "LOD " << lod;
            ASSERT_LT(d, edges[lod + 1] + half + 1e-3f) << "LOD " << lod;
            float t = float(p.fade & 0xffu) / 255.0f;
            bool upper = (p.fade & 0x10000u) != 0;
            bool inBand = std::abs(d - edges[lod + (upper ? 0 : 1)]) < half;
            if (t > 0.0f || upper) {
                ++banded;
                EXPECT_TRUE(inBand) << "only plants in a band fade";
            }
            upperCopies += upper;
        }
        begin = end;
    }
    EXPECT_GT(banded, 0u);
    EXPECT_GT(upperCopies, 0u) << "plants in the near/mid and mid/far bands are drawn in both LODs";
}

// Far slicing (LodParams::sliceLayers: far billboards drawn only above the height a grazing ray reaches) and merging
// (LodParams::mergeWidth: fewer, wider far billboards): the same vegetation coverage and mean colour in the images,
// from fewer billboards and fewer fragments; near and mid plants untouched.
TEST_F(VegetationTest, SlicingAndMergingFarBillboardsKeepCoverageAndColour) {
    struct Measured {
        gpu::ExpansionStats stats{};
        double plants = 0.0, green = 0.0, farHeight = 0.0; // farHeight: drawn share of the far billboards' height
    };
    auto measure = [&](float sliceLayers, float mergeWidth, float depthMerge) {
        scene.lod.sliceLayers = sliceLayers;
        scene.lod.mergeWidth = mergeWidth;
        scene.lod.depthMerge = depthMerge;
        auto r = renderer(true);
        Measured m;
        FrameImages frame = renderFrame(*ctx, *r, camera);
        m.stats = r->vegetation()->readStats();
        const std::vector<gpu::ExpandedPlant> instances = readInstances(*r->vegetation(), m.stats.instances.w);
        const uint32_t firstFar = m.stats.instances.x + m.stats.instances.y;
        for (uint32_t i = firstFar; i < m.stats.instances.w; ++i) // cut height / plant height; the base is at v = 1
            m.farHeight += 1.0 - float(instances[i].attributes >> 24) / gpu::kSliceUnit;
        m.farHeight /= std::max(double(m.stats.instances.z), 1.0);
        for (size_t i = 0; i < frame.labels.size(); ++i) {
            uint32_t semantic = frame.labels[i] >> gpu::kInstanceBits;
            if (semantic < gpu::kSemanticVegetation || semantic >= gpu::kSemanticVegetation + gpu::kMaxPlantCategories)
                continue;
            m.plants += 1.0;
            m.green += halfBitsToFloat(frame.rgbaHalf[4 * i + 1]);
        }
        m.green /= std::max(m.plants, 1.0);
        return m;
    };
    // Fewer layers than the default: a test that can fail.
    const Measured whole = measure(0.0f, 0.0f, 0.0f), sliced = measure(4.0f, 6.0f, 0.0f),
                   deep = measure(4.0f, 6.0f, 16.0f);
    std::printf(
        "far plants %u -> %u, drawn share of their height %.3f, plant pixels %.0f -> %.0f (%+.2f %%), mean green "
        "%.4f -> %.4f (%+.2f %%)\n",
        whole.stats.instances.z, sliced.stats.instances.z, sliced.farHeight, whole.plants, sliced.plants,
        100.0 * (sliced.plants / whole.plants - 1.0), whole.green, sliced.green,
        100.0 * (sliced.green / whole.green - 1.0));
    EXPECT_EQ(sliced.stats.instances.x, whole.stats.instances.x) << "near plants are never sliced";
    EXPECT_EQ(sliced.stats.instances.y, whole.stats.instances.y) << "mid plants are never sliced";
    EXPECT_EQ(whole.farHeight, 1.0) << "off: every far billboard whole";
    EXPECT_LT(sliced.farHeight, 0.85) << "the hidden parts of far billboards are not drawn";
    EXPECT_LT(sliced.stats.instances.z, whole.stats.instances.z / 2)
        << "at 240 x 160 far billboards are a few pixels wide";
    ASSERT_GT(whole.plants, double(kWidth * kHeight) / 5);
    EXPECT_NEAR(sliced.plants / whole.plants, 1.0, 0.02) << "coverage within 2 %";
    EXPECT_NEAR(sliced.green / whole.green, 1.0, 0.02) << "mean plant colour within 2 %";
    // Merged in depth too (LodParams::depthMerge): fewer, denser far cards, the same coverage and colour.
    std::printf("merged in depth: far plants %u, plant pixels %.0f (%+.2f %%), mean green %.4f (%+.2f %%)\n",
                deep.stats.instances.z, deep.plants, 100.0 * (deep.plants / whole.plants - 1.0), deep.green,
                100.0 * (deep.green / whole.green - 1.0));
    EXPECT_EQ(deep.stats.instances.y, whole.stats.instances.y) << "mid plants are never merged";
    EXPECT_LT(deep.stats.instances.z, sliced.stats.instances.z * 0.85) << "fewer far billboards";
    EXPECT_NEAR(deep.plants / whole.plants, 1.0, 0.02) << "coverage within 2 %";
    EXPECT_NEAR(deep.green / whole.green, 1.0, 0.02) << "mean plant colour within 2 %";
}

// A merged far billboard (LodParams::mergeWidth) is drawn wider than its plant: it shows copies of the plant side by
// side (plant_fragment.glsl, plantTexel), not one plant stretched, so the far plants keep their detail across the
// image (here the mean difference of green between horizontal neighbours), as they keep it up the image.
TEST_F(VegetationTest, MergedFarBillboardsKeepTheirDetailAcrossTheImage) {
    struct Detail {
        double across = 0.0, up = 0.0;
        uint64_t pairs = 0;
    };
    // Across the tile's diagonal, just above the plants, so that far plants fill much of the image.
    const glm::dvec3 eye(3.0, 3.0, terrain.height({3.0f, 3.0f}) + 1.0);
    const glm::dvec3 target(97.0, 97.0, terrain.height({97.0f, 97.0f}) + 0.3);
    const Camera grazing = Camera::lookAt(eye, target, {0, 0, 1}, 30.0, kWidth, kHeight);
    auto measure = [&](float mergeWidth, float depthMerge) {
        scene.lod.mergeWidth = mergeWidth;
        scene.lod.depthMerge = depthMerge;
        auto r = renderer(true);
        FrameImages frame = renderFrame(*ctx, *r, grazing);
        auto farPlant = [&](size_t i) {
            const uint32_t semantic = frame.labels[i] >> gpu::kInstanceBits;
            return semantic >= gpu::kSemanticVegetation &&
                   semantic < gpu::kSemanticVegetation + gpu::kMaxPlantCategories &&
                   frame.depth[i] > scene.lod.midToFar + scene.lod.band;
        };
        auto green = [&](size_t i) { return double(halfBitsToFloat(frame.rgbaHalf[4 * i + 1])); };
        Detail d;
        for (uint32_t y = 1; y < kHeight; ++y)
            for (uint32_t x = 1; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                if (!farPlant(i) || !farPlant(i - 1) || !farPlant(i - kWidth)) continue; // one far plant or another
                d.across += std::abs(green(i) - green(i - 1));
                d.up += std::abs(green(i) - green(i - kWidth));
                ++d.pairs;
            }
        d.across /= std::max<double>(double(d.pairs), 1.0);
        d.up /= std::max<double>(double(d.pairs), 1.0);
        return d;
    };
    const Detail whole = measure(0.0f, 0.0f), merged = measure(12.0f, 0.0f), deep = measure(12.0f, 16.0f);
    std::printf("far plant pixels %llu / %llu, detail across %.4f -> %.4f, up %.4f -> %.4f\n",
                (unsigned long long)whole.pairs, (unsigned long long)merged.pairs, whole.across, merged.across,
                whole.up, merged.up);
    ASSERT_GT(whole.pairs, uint64_t(kWidth * kHeight / 20)) << "too few far plant pixels to measure";
    EXPECT_NEAR(merged.across / whole.across, 1.0, 0.05) << "detail across the image within 5 %";
    EXPECT_NEAR(merged.up / whole.up, 1.0, 0.05) << "detail up the image within 5 %";
    std::printf("merged in depth too: far plant pixels %llu, detail across %.4f, up %.4f\n",
                (unsigned long long)deep.pairs, deep.across, deep.up);
    EXPECT_NEAR(deep.across / whole.across, 1.0, 0.05) << "merged in depth: detail across the image within 5 %";
    EXPECT_NEAR(deep.up / whole.up, 1.0, 0.05) << "merged in depth: detail up the image within 5 %";
}

TEST_F(VegetationTest, ClusterCullingSkipsWhatTheCameraCannotSee) {
    auto r = renderer(true);
    renderFrame(*ctx, *r, camera);
    gpu::ExpansionStats ground = r->vegetation()->readStats();
    EXPECT_GT(ground.info.x, 0u);
    EXPECT_LT(ground.info.x, r->vegetation()->buffers().clusterCount / 2) << "most clusters are outside the view";

    Camera sky = Camera::lookAt(camera.position, camera.position + glm::dvec3(0.0, 0.1, 10.0), {0, 0, 1}, 40.0,
                                kWidth, kHeight);
    renderFrame(*ctx, *r, sky);
    gpu::ExpansionStats up = r->vegetation()->readStats();
    EXPECT_EQ(up.info.x, 0u) << "looking at the sky, no cluster is visible";
    EXPECT_EQ(up.instances.w, 0u);
}

// Cut-out quads rasterise other triangles over the same planes: a pixel's surface, and so its label, stays the same
// unless a texel kept by the alpha test fell outside the polygon (a mip coarser than kCutoutMaxLevel, see
// vegetation/atlas_cutout.h), while interpolated depth and colour may change in their last bits. Where the alpha
// test sits right at its threshold, that last bit may also let another quad of the same plant win the pixel: its
// label is the same, its depth a few centimetres off.
TEST_F(VegetationTest, CutoutsKeepThePlantPixelsAndTheirDepthToRounding) {
    for (uint32_t samples : {1u, 4u}) {
        auto r = renderer(true, samples);
        FrameImages quads = renderFrame(*ctx, *r, camera);
        r->vegetation()->setCutout(8, atlas);
        FrameImages cut = renderFrame(*ctx, *r, camera);
        size_t plants = 0, labelsDiffer = 0, depthBitsDiffer = 0, otherSurface = 0;
        for (size_t i = 0; i < quads.labels.size(); ++i) {
            const uint32_t semantic = quads.labels[i] >> gpu::kInstanceBits;
            plants += semantic >= gpu::kSemanticVegetation && semantic < gpu::kSemanticObject;
            if (quads.labels[i] != cut.labels[i]) {
                ++labelsDiffer;
                continue;
            }
            if (!std::isfinite(quads.depth[i])) continue;
            depthBitsDiffer += quads.depth[i] != cut.depth[i];
            otherSurface += std::abs(quads.depth[i] - cut.depth[i]) > 1e-5f * quads.depth[i];
        }
        std::printf("%ux: %zu plant pixels; labels differ at %zu, depth bits at %zu, by more than 1e-5 at %zu\n",
                    samples, plants, labelsDiffer, depthBitsDiffer, otherSurface);
        ASSERT_GT(plants, quads.labels.size() / 4);
        EXPECT_LE(labelsDiffer, plants / 1000) << samples << "x";
        EXPECT_LE(otherSurface, plants / 1000) << samples << "x";
    }
}
