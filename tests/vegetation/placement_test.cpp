// Acceptance tests of issue 4: reproducible, density-faithful placement on the ground, in compact records.
#include "world/gltf_mesh.h"
#include "io/image_files.h"
#include "io/image_io.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace sward;
using namespace sward::test;

namespace {

// A 100 x 100 m tile (4 x 4 fields of 25 m, 5 m clusters) over hilly terrain, with a meadow map.
VegetationParams smallTileParams() {
    VegetationParams p;
    p.tileSize = 100.0f;
    p.seed = 11;
    return p;
}

const Ground& hills() {
    static const Ground ground(
        makeProceduralTerrain({.size = 100.0f, .spacing = 2.0f, .amplitude = 15.0f, .featureSize = 40.0f, .seed = 5}));
    return ground;
}

const GrassMap& meadow() {
    static const GrassMap map = makeMeadowGrassMap({.resolution = 64, .tileSize = 100.0f, .seed = 2});
    return map;
}

bool sameBytes(const FieldVegetation& a, const FieldVegetation& b) {
    auto same = [](const auto& x, const auto& y) {
        return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
    };
    return same(a.staticRecords, b.staticRecords) && same(a.dynamicRecords, b.dynamicRecords) &&
           same(a.clusters, b.clusters);
}

bool sameTiles(const VegetationTile& a, const VegetationTile& b) {
    if (a.fields.size() != b.fields.size()) return false;
    for (size_t i = 0; i < a.fields.size(); ++i)
        if (!sameBytes(a.fields[i], b.fields[i])) return false;
    return true;
}

// Every plant of a tile with its decoded world position and its cluster.
template <class F> void forEachPlant(const VegetationTile& tile, F f) {
    for (const FieldVegetation& field : tile.fields)
        for (const gpu::PlantCluster& c : field.clusters)
            for (uint32_t i = c.range.x; i < c.range.x + c.range.y; ++i)
                f(field, c, field.staticRecords[i],
                  decodePlantPosition(field.staticRecords[i], field.origin, field.positionStep));
}

} // namespace

TEST(Placement, FieldRegeneratedAloneIsByteIdenticalToTheTile) {
    const VegetationTile tile = generateTile(hills(), meadow(), smallTileParams(), {}, 2);
    const FieldVegetation alone = generateField(hills(), meadow(), smallTileParams(), {}, {2, 3});
    ASSERT_GT(alone.plantCount(), 1000u);
    EXPECT_TRUE(sameBytes(alone, tile.field({2, 3})));
}

TEST(Placement, OutputIsIdenticalWithOneAndFourThreads) {
    EXPECT_TRUE(sameTiles(generateTile(hills(), meadow(), smallTileParams(), {}, 1),
                          generateTile(hills(), meadow(), smallTileParams(), {}, 4)));
}

TEST(Placement, DifferentSeedChangesThePlants) {
    VegetationParams other = smallTileParams();
    other.seed += 1;
    EXPECT_FALSE(sameBytes(generateField(hills(), meadow(), smallTileParams(), {}, {1, 1}),
                           generateField(hills(), meadow(), other, {}, {1, 1})));
}

TEST(Placement, AdjacentTileIsPlacedInItsOwnAreaAndDiffers) {
    const Ground wide(makeProceduralTerrain({.size = 200.0f, .spacing = 2.0f, .seed = 5}));
    const VegetationTile west = generateTile(wide, meadow(), smallTileParams(), {0, 0}, 2);
    const VegetationTile east = generateTile(wide, meadow(), smallTileParams(), {1, 0}, 2);
    EXPECT_EQ(east.origin, glm::vec2(100.0f, 0.0f));
    forEachPlant(east, [](auto&, auto&, auto&, glm::vec3 p) {
        ASSERT_GE(p.x, 100.0f);
        ASSERT_LE(p.x, 200.0f);
    });
    EXPECT_FALSE(sameBytes(west.fields[0], east.fields[0]));
}

// Tolerance: the count of a cluster is floor(I8 + u), with I8 the 8x8 midpoint integral of the bilinear density,
// so |count - I8| < 1; the midpoint rule differs from the exact integral I by the bilinear kinks at pixel edges,
// bounded here by 2% of I. Over the whole tile the +-1 rounding errors are independent with mean zero, so the
// total stays within 0.5% of the exact prediction (about 8 standard deviations for this tile).
TEST(Placement, ClusterCountsMatchTheDensityIntegral) {
    const VegetationParams p = smallTileParams();
    const Ground flat(Heightfield(2, 2, 100.0f, glm::vec2(0.0f), {0, 0, 0, 0}));
    const VegetationTile tile = generateTile(flat, meadow(), p, {}, 2);
    uint64_t total = 0;
    for (const FieldVegetation& field : tile.fields) {
        for (uint32_t k = 0; k < field.clusters.size(); ++k) {
            const glm::vec2 lo = field.origin + glm::vec2(k % 5, k / 5) * p.clusterSize;
            double integral = 0.0;
            const int n = 50;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const glm::vec4 m =
                        meadow().sample((lo + (glm::vec2(i, j) + 0.5f) * (p.clusterSize / n)) / p.tileSize);
                    for (uint32_t c = 0; c < 3; ++c) integral += m[int(c)] * p.categories[c].density;
                }
            integral *= double(p.clusterSize * p.clusterSize) / (n * n);
            const double count = field.clusters[k].range.y;
            // Three categories round independently: at most one plant each.
            ASSERT_NEAR(count, integral, 3.0 + 0.02 * integral) << "field " << field.coord.x << "," << field.coord.y;
            total += field.clusters[k].range.y;
        }
    }
    EXPECT_NEAR(double(total), predictPlantCount(meadow(), p), 0.005 * predictPlantCount(meadow(), p));
}

TEST(Placement, EveryPlantLiesOnTheTerrainAndInsideItsClusterBox) {
    const VegetationTile tile = generateTile(hills(), meadow(), smallTileParams(), {}, 2);
    uint64_t plants = 0;
    forEachPlant(tile, [&](auto&, const gpu::PlantCluster& c, auto&, glm::vec3 p) {
        ++plants;
        ASSERT_NEAR(p.z, hills().surface(glm::vec2(p))->height, 1e-3f);
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, glm::vec3(c.boundsMin))));
        ASSERT_TRUE(glm::all(glm::lessThanEqual(p, glm::vec3(c.boundsMax))));
    });
    EXPECT_EQ(plants, countVegetation(tile).plants);
}

TEST(Placement, ClusterBoxesIncludeThePlantHeight) {
    const VegetationParams p = smallTileParams();
    const VegetationTile tile = generateTile(hills(), meadow(), p, {}, 2);
    forEachPlant(tile, [&](auto&, const gpu::PlantCluster& c, const gpu::PlantStatic& r, glm::vec3 pos) {
        const PlantInstance plant = decodePlantStatic(r);
        const float height = p.categories[plant.category].height * float(plant.size) / gpu::kPlantSizeDivisor;
        ASSERT_GE(c.boundsMax.z, pos.z + height);
    });
}

TEST(Placement, PlantsFollowTheGltfMeshGround) {
    const auto path = tempDir() / "ground.gltf";
    // A 100 x 100 m tent roof (two slopes meeting at x = 50) as glTF Y-up, embedded buffer.
    const float v[6][3] = {{0, 0, 0}, {50, 10, 0}, {100, 0, 0}, {0, 0, -100}, {50, 10, -100}, {100, 0, -100}};
    const uint32_t idx[12] = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    std::vector<uint8_t> bytes(sizeof v + sizeof idx);
    std::memcpy(bytes.data(), v, sizeof v);
    std::memcpy(bytes.data() + sizeof v, idx, sizeof idx);
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5125, "count": 12, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
      "buffers": [{"byteLength": 120, "uri": "data:application/octet-stream;base64,)"
                        << base64(bytes) << R"("}]})";
    const Ground roof(loadGltfMesh(path.string()));
    VegetationParams p = smallTileParams();
    p.upNormalBlend = 1.0f;
    const VegetationTile tile = generateTile(roof, meadow(), p, {}, 2);
    ASSERT_GT(countVegetation(tile).plants, 10000u);
    forEachPlant(tile, [&](auto&, auto&, const gpu::PlantStatic& r, glm::vec3 pos) {
        const float expected = 10.0f - std::abs(pos.x - 50.0f) * 0.2f; // roof height
        ASSERT_NEAR(pos.z, expected, 1e-3f);
        const glm::vec3 up = decodeOctahedral(r.up);
        ASSERT_NEAR(up.x, pos.x < 50.0f ? -0.196f : 0.196f, std::abs(pos.x - 50.0f) < 1e-3f ? 1.0f : 1e-3f);
    });
}

TEST(Placement, UpVectorBlendsBetweenWorldUpAndNormal) {
    VegetationParams p = smallTileParams();
    p.upNormalBlend = 0.0f;
    const FieldVegetation upright = generateField(hills(), meadow(), p, {}, {1, 2});
    for (const gpu::PlantStatic& r : upright.staticRecords) ASSERT_EQ(decodeOctahedral(r.up), glm::vec3(0, 0, 1));
    p.upNormalBlend = 1.0f;
    const FieldVegetation normal = generateField(hills(), meadow(), p, {}, {1, 2});
    for (const gpu::PlantStatic& r : normal.staticRecords) {
        const glm::vec3 pos = decodePlantPosition(r, normal.origin, normal.positionStep);
        ASSERT_LT(glm::length(decodeOctahedral(r.up) - hills().surface(glm::vec2(pos))->normal), 1e-4f);
    }
}

TEST(Placement, ThreeChannelMapPutsEachCategoryInItsRegion) {
    // 30 px over 100 m: west third red (ferns), middle green (grass), east third blue (flowers).
    std::vector<float> px(30 * 30 * 3, 0.0f);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 30; ++x) px[(y * 30 + x) * 3 + x / 10] = 1.0f;
    const GrassMap map(30, 30, 3, px, "thirds");
    const VegetationTile tile = generateTile(hills(), map, smallTileParams(), {}, 2);
    uint32_t seen[3] = {};
    forEachPlant(tile, [&](auto&, auto&, const gpu::PlantStatic& r, glm::vec3 pos) {
        const uint32_t category = decodePlantStatic(r).category;
        ++seen[category];
        // Bilinear blending reaches one pixel (3.3 m) across each border.
        const uint32_t expected = pos.x < 30.0f                      ? 0u
                                  : (pos.x > 37.0f && pos.x < 63.0f) ? 1u
                                  : pos.x > 70.0f                    ? 2u
                                                                     : category;
        ASSERT_EQ(category, expected) << "at x = " << pos.x;
    });
    EXPECT_GT(seen[0], 1000u);
    EXPECT_GT(seen[1], 10000u);
    EXPECT_GT(seen[2], 500u);
}

TEST(Placement, StratifiedJitterLeavesNoClumpsOrHoles) {
    // Uniform grass at 16 plants/m^2: each 1 m^2 cell of a cluster expects 16 plants. Independent uniform points
    // would put a Poisson count there (sd 4, so cells of < 8 or > 24 plants are common among 2,500 cells);
    // strata of 1/16 m^2 keep every count close to 16.
    const GrassMap map(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    const Ground flat(Heightfield(2, 2, 100.0f, glm::vec2(0.0f), {0, 0, 0, 0}));
    const VegetationTile tile = generateTile(flat, map, smallTileParams(), {}, 2);
    std::vector<uint32_t> cells(100 * 100, 0);
    forEachPlant(tile, [&](auto&, auto&, auto&, glm::vec3 p) {
        ++cells[std::min(int(p.y), 99) * 100 + std::min(int(p.x), 99)];
    });
    for (uint32_t c : cells) {
        ASSERT_GE(c, 8u);
        ASSERT_LE(c, 24u);
    }
}

TEST(Placement, FieldBuffersArePackedInFieldOrder) {
    const VegetationTile tile = generateTile(hills(), meadow(), smallTileParams(), {}, 2);
    const std::vector<gpu::PlantField> table = makeFieldTable(tile);
    ASSERT_EQ(table.size(), 16u);
    EXPECT_EQ(table[1].range.x, tile.fields[0].plantCount());
    EXPECT_EQ(tile.fields[1].staticRange.offset, tile.fields[0].plantCount() * sizeof(gpu::PlantStatic));
    EXPECT_EQ(tile.fields[1].dynamicRange.offset, tile.fields[0].plantCount() * sizeof(gpu::PlantDynamic));
    EXPECT_EQ(table[3].range.z, 3u * 25u);
    EXPECT_EQ(countVegetation(tile).totalBytes(), countVegetation(tile).plants * 24 + 16 * 25 * 48);
}

TEST(PlacementErrors, DensityOverTheMemoryBudgetFailsBeforeAllocating) {
    VegetationParams p = smallTileParams();
    p.memoryBudgetBytes = 1 << 20; // 1 MiB: about 43,000 plants, the meadow needs more
    expectError([&] { generateTile(hills(), meadow(), p, {}, 1); },
                {meadow().source(), "memory budget", "1 MiB", "memory_budget_mib"});
}

TEST(PlacementErrors, HugeDensityFromAFileNamesTheFile) {
    const auto path = (tempDir() / "dense.exr").string();
    writeExr(path, 1, 1, 3, {0.0f, 1.0e6f, 0.0f}); // a million times full intensity
    const GrassMap map = loadGrassMap(path);
    expectError([&] { generateTile(hills(), map, smallTileParams(), {}, 1); }, {path, "plants per tile"});
}
