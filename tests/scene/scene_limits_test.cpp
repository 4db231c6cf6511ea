// Limits of a scene file: counts that scale memory, time or id spaces are refused while parsing.
#include "common/error.h"
#include "scene/scene.h"
#include "scene/scene_limits.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <functional>

using namespace sward;
using sward::test::errorOf;

namespace {

std::string parseError(const nlohmann::json& json) {
    return errorOf([&] { parseScene(json, "s.json"); });
}

nlohmann::json repeated(const nlohmann::json& element, size_t count) {
    return nlohmann::json(std::vector<nlohmann::json>(count, element));
}

} // namespace

TEST(SceneLimits, GustsTimesFramesAreBoundedBeforeAnythingIsBuilt) {
    // The issue's 100,000 gusts over 200 frames: 20 M collider records (std::bad_alloc after 7.8 GB before).
    EXPECT_EQ(parseError({{"gusts", {{"count", 100000}}}, {"sequence", {{"frames", 200}}}}),
              "s.json: 'sequence.frames' (200) times 100000 colliders per frame ('gusts.count' 100000, 4 per vehicle, "
              "'colliders', the objects' 'colliders') is 20000000 collider records in frames.jsonl, over the limit of "
              "2000000; lower 'gusts.count' or 'sequence.frames'");
    EXPECT_NO_THROW(parseScene({{"gusts", {{"count", 100000}}}, {"sequence", {{"frames", 20}}}}, "s.json"))
        << "exactly at the limit";
}

TEST(SceneLimits, VehiclesAndCollidersStayWithinTheirColliderIds) {
    const nlohmann::json path = {{"points", {{0, 0}, {1, 0}}}};
    EXPECT_EQ(parseError({{"vehicles", repeated({{"path", path}}, kMaxVehicles + 1)}}),
              "s.json: 'vehicles' has 100 entries, over the limit of 99 (the wheel collider ids)");
    EXPECT_NO_THROW(parseScene({{"vehicles", repeated({{"path", path}}, kMaxVehicles)}}, "s.json"));
    EXPECT_EQ(parseError({{"colliders", repeated({{"path", path}}, kMaxFreeColliders + 1)}}),
              "s.json: 'colliders' has 100001 entries, over the limit of 100000 (the collider ids)");
}

TEST(SceneLimits, ObjectCountIsCheckedBeforeAnyObjectIsParsed) {
    // The elements are not even valid objects: the count is refused first, without parsing 10,001 entries.
    EXPECT_EQ(parseError({{"objects", repeated(1, kMaxSceneObjects + 1)}}),
              "s.json: 'objects' has 10001 entries, over the limit of 10000 (models to load, instance ids)");
}

TEST(SceneLimits, TheIssuesDenseMeadowIsRefusedBeforePlacingItsPlants) {
    // density_multiplier 12 on the default meadow predicts ~33 M plants: classes and instance ids wrapped before.
    const Scene scene = parseScene({{"vegetation", {{"density_multiplier", 12}}}}, "s.json");
    const Ground terrain = buildTerrain(scene);
    const std::string error = errorOf([&] { buildVegetation(scene, terrain, 1); });
    EXPECT_NE(error.find("its densities predict"), std::string::npos) << error;
    EXPECT_NE(error.find("plants per tile, over the limit of 15999999"), std::string::npos) << error;
    EXPECT_NE(error.find("'vegetation.density_multiplier'"), std::string::npos) << error;
}

TEST(SceneLimits, ResolutionsThatWouldWrapAreRefused) {
    uint32_t w = 0, h = 0;
    // 4294967616 = 2^32 + 320: sscanf's %u wrapped it to 320.
    for (const char* bad : {"4294967616x240", "320x4294967536", "18446744073709551936x240", "99999999999999999999x1",
                            "+320x240", "320x 240"})
        EXPECT_THROW(parseResolution(bad, w, h), Error) << bad;
    parseResolution("16384X1", w, h);
    EXPECT_EQ(w, 16384u);
    EXPECT_EQ(h, 1u);
}

TEST(SceneLimits, ASceneResolutionOverThePixelLimitIsRefusedWithItsImagesBytes) {
    // 16384x16384 reached VK_ERROR_OUT_OF_DEVICE_MEMORY; the command line already refused it.
    EXPECT_EQ(parseError({{"render", {{"resolution", {16384, 16384}}, {"samples", 4}}}}),
              "s.json: 'render.resolution' 16384x16384 is 268435456 pixels (about 30720 MiB of render images), over "
              "the limit of 67108864 (8192x8192)");
    EXPECT_NO_THROW(parseScene({{"render", {{"resolution", {16384, 4096}}}}}, "s.json")) << "exactly at the limit";
}

TEST(SceneLimits, AProceduralTerrainIsPricedAsAHeightmapIs) {
    // 8000 cells a side took 54 s and 10 GB for a 32x24 render.
    EXPECT_EQ(parseError({{"terrain", {{"size", 4000}, {"spacing", 0.5}}}}),
              "s.json: 'terrain.size' / 'terrain.spacing' exceeds 4096 cells a side: its ground would take about "
              "5860 MiB");
    // Exactly at the limit (such a tile's default meadow is refused for its plant count instead).
    EXPECT_EQ(parseError({{"terrain", {{"size", 2048}, {"spacing", 0.5}}}}).find("cells"), std::string::npos);
}
