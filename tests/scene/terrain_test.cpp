// The scene's ground from the example worlds' generated files (tools/make-example-data.py): the GeoTIFF heightmap
// in metres against its closed-form surface, and the land-cover map's pond left bare.
#include "scene/scene.h"
#include "vegetation/records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace sward;

namespace {

const std::string kGis = std::string(SWARD_EXAMPLES_DIR) + "/gis/gis.json";

// dem_height of tools/make-example-data.py: metres at (x, y) metres east / north of the south-west sample.
double demHeight(double x, double y) {
    return 40.0 + 6.0 * std::sin(2 * std::numbers::pi * x / 256.0) * std::cos(2 * std::numbers::pi * y / 192.0) +
           0.02 * x - 0.01 * y;
}

} // namespace

TEST(Terrain, GeoTiffHeightmapInMetresMatchesItsAnalyticSurface) {
    const Scene scene = loadScene(kGis);
    const Ground ground = buildTerrain(scene);
    ASSERT_NE(ground.heightfield(), nullptr);
    const Heightfield& h = *ground.heightfield();
    EXPECT_EQ(h.columns(), 257u);
    EXPECT_EQ(h.rows(), 257u);
    EXPECT_EQ(h.spacing(), 2.0f); // from the GeoTIFF's georeferencing (UTM, metres)
    EXPECT_EQ(ground.boundsMin(), glm::vec2(0.0f));
    EXPECT_EQ(ground.boundsMax(), glm::vec2(512.0f));
    // At the samples: the stored float32 (written with 6 decimals) exactly where it should be.
    for (uint32_t j = 0; j < h.rows(); j += 16)
        for (uint32_t i = 0; i < h.columns(); i += 16)
            ASSERT_NEAR(ground.surface(glm::vec2(2.0f * float(i), 2.0f * float(j)))->height,
                        demHeight(2.0 * i, 2.0 * j), 2e-5)
                << "sample " << i << ", " << j;
    // Between samples: the triangulation's error is bounded by the surface's curvature, 6 (2 pi / 192)^2 m^-1 over
    // a 2 m cell: well under 1 cm.
    for (int k = 0; k < 200; ++k) {
        const double x = 0.37 + 2.5531 * k, y = 511.0 - 2.3917 * k;
        ASSERT_NEAR(ground.surface(glm::vec2(float(x), float(y)))->height, demHeight(x, y), 0.01) << x << ", " << y;
    }
}

TEST(Terrain, LandCoverWaterStaysBareAndTheTileCoversTheHeightmap) {
    const Scene scene = loadScene(kGis);
    const Ground ground = buildTerrain(scene);
    const VegetationTile tile = buildVegetation(scene, ground, 2);
    EXPECT_EQ(tile.size, 500.0f);
    uint64_t plants = 0;
    for (const FieldVegetation& field : tile.fields)
        for (const gpu::PlantStatic& record : field.staticRecords) {
            const glm::vec3 p = decodePlantPosition(record, field.origin, field.positionStep);
            ++plants;
            // The pond (WorldCover 80: no plants) is the 4 m pixels whose centres lie within 45 m of (380, 140); the
            // 8 m soft border reaches 4 m in.
            // Slack: half the border, one pixel of bilinear reconstruction, half a pixel diagonal of the disc edge.
            const double d = std::hypot(p.x - 380.0, p.y - 140.0);
            if (d < 45.0 - 4.0 - 4.0 - 2.9) ADD_FAILURE() << "a plant in the pond, " << d << " m from its centre";
            ASSERT_NEAR(p.z, ground.surface(glm::vec2(p))->height, 1e-3f);
        }
    EXPECT_GT(plants, 100000u);
}
