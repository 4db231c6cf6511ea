// Limits of placement: the plant instance-id space and the memory of the tile's records, refused up front.
#include "vegetation/placement.h"

#include "shared/gpu_layout.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <functional>

#include <unistd.h>

using namespace sward;
using sward::test::errorOf;
using namespace sward::test;

namespace {

// Full intensity in every channel: the predicted count is exact arithmetic on the densities.
GrassMap uniformMap(float intensity) {
    return GrassMap(1, 1, 4, {intensity, intensity, intensity, intensity}, "uniform");
}

const Ground& flat() {
    static const Ground ground(makeProceduralTerrain({.size = 100.0f, .spacing = 5.0f, .amplitude = 0.0f, .seed = 1}));
    return ground;
}

} // namespace

TEST(PlacementLimits, PlantIdsFitUpToTheObjectBase) {
    EXPECT_EQ(gpu::kMaxPlantInstances, gpu::kInstanceObjectBase - 1) << "plant ids are plant index + 1";
    EXPECT_NO_THROW(checkPlantIdSpace(gpu::kMaxPlantInstances, "t:"));
    EXPECT_EQ(errorOf([] { checkPlantIdSpace(gpu::kMaxPlantInstances + 1ull, "t: placed"); }),
              "t: placed 16000000 plants per tile, over the limit of 15999999 (the plant instance ids of the "
              "ground-truth labels); lower 'vegetation.density_multiplier', the categories' 'density' or "
              "'vegetation.tile_size'");
    // Objects take the rest of the 24-bit id space.
    EXPECT_EQ(gpu::kInstanceObjectBase + gpu::kMaxObjectInstances, 1u << gpu::kInstanceBits);
}

TEST(PlacementLimits, MorePlantsThanInstanceIdsAreRefusedBeforePlacement) {
    // 100 x 100 m at 16 grass plants per m^2 times 100: 16,000,000 predicted plants, one over the id space. The
    // records (384 MiB) fit the default budget, so only the id check stands between this and a wrapped dataset.
    VegetationParams p;
    p.tileSize = 100.0f;
    p.densityMultiplier = 100.0f;
    p.categories[0].density = 0.0f;
    p.categories[2].density = 0.0f;
    p.channelCategory = {0, 1, 2, kUnusedChannel};
    EXPECT_NEAR(predictPlantCount(uniformMap(1.0f), p), 16e6, 1.0);
    const std::string error = errorOf([&] { generateTile(flat(), uniformMap(1.0f), p, {}, 1); });
    EXPECT_NE(error.find("grass map 'uniform': its densities predict 16000000 plants per tile, over the limit of 15999999"),
              std::string::npos)
        << error;
}

TEST(PlacementLimits, ClusterRecordsCountAgainstTheMemoryBudget) {
    // No plants at all, but 65536 m / 1 m clusters: 4,294,967,296 cluster records of 48 bytes (192 GiB).
    VegetationParams p;
    p.tileSize = 65536.0f;
    p.fieldSize = 64.0f;
    p.clusterSize = 1.0f;
    const std::string error = errorOf([&] { generateTile(flat(), uniformMap(0.0f), p, {}, 1); });
    EXPECT_NE(error.find("0 plants per tile in 4294967296 clusters (196608 MiB of records), over the vegetation "
                         "memory budget of 1024 MiB"),
              std::string::npos)
        << error;
}

TEST(PlacementLimits, ABudgetAbovePhysicalMemoryIsRefusedBeforeAllocating) {
    const uint64_t physical = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
    if (physical >= (uint64_t(192) << 30)) GTEST_SKIP() << "this machine holds the 192 GiB of cluster records";
    VegetationParams p;
    p.tileSize = 65536.0f;
    p.fieldSize = 64.0f;
    p.clusterSize = 1.0f;
    p.memoryBudgetBytes = uint64_t(1) << 40;
    const std::string error = errorOf([&] { generateTile(flat(), uniformMap(0.0f), p, {}, 1); });
    EXPECT_NE(error.find("over this machine's physical memory"), std::string::npos) << error;
}
