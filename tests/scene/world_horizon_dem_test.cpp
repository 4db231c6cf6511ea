// The horizon ring of a DEM world (scene/world_horizon.h): one stepped read of the DEM (GDAL builds only).
#include "common/error.h"
#include "scene/scene.h"
#include "scene/world_ground.h"
#include "scene/world_horizon.h"
#include "world/heightfield.h"

#include "dem_files.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace sward;

namespace {

std::string parseError(const nlohmann::json& json) {
    try {
        parseScene(json, "dem horizon.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

// A DEM world's ring is every k-th DEM sample, bitwise the tiles' (worldHeights over the whole world), in one stepped
// read; it ends at the last ring line inside the DEM.
TEST(WorldHorizon, ADemWorldsRingHoldsEveryKthSampleOfTheDem) {
    const std::string path = (test::tempDir() / "horizon-dem.tif").string();
    test::writeDem(path, {.columns = 63, .rows = 43, .spacing = 1.0, .height = [](uint32_t c, uint32_t r) {
                              return 10.0 + 0.05 * c - 0.03 * r + 0.002 * (c - 30.0) * (c - 30.0) + 0.001 * c * r;
                          }});
    nlohmann::json json = {{"seed", 3},
                           {"terrain", {{"heightmap", {{"file", path}}}}},
                           {"vegetation", {{"tile_size", 20}, {"field_size", 10}}},
                           {"vegetation_enabled", false},
                           {"world",
                            {{"tiles", {3, 2}},
                             {"load_radius", 15},
                             {"evict_radius", 30},
                             {"memory_budget_mib", 64},
                             {"horizon", {{"spacing", 3}}}}}};
    const Scene scene = parseScene(json, "dem horizon.json");
    const Heightfield ring = horizonHeights(scene);
    EXPECT_EQ(ring.columns(), 21u); // 60 m / 3 m + 1
    EXPECT_EQ(ring.rows(), 15u);    // 40 m / 3 m = 13.3 cells, rounded up: 14, the DEM's 43 rows hold them
    const glm::dvec2 lo(scene.vegetation.worldOrigin);
    const Heightfield all = worldHeights(scene, lo, lo + glm::dvec2(60.0, 42.0));
    for (uint32_t j = 0; j < ring.rows(); ++j)
        for (uint32_t i = 0; i < ring.columns(); ++i)
            ASSERT_EQ(ring.sample(i, j), all.sample(3 * i, 3 * j)) << i << "," << j;
    json["world"]["horizon"] = {{"spacing", 2.5}};
    EXPECT_NE(parseError(json).find("must be a whole multiple of the DEM's sample spacing (1 m)"), std::string::npos)
        << parseError(json);
}
