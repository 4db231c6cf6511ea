// Compact tile interaction state and the world state file. CPU only.
#include "interaction/state_file.h"
#include "interaction/tile_state.h"

#include "interaction_world.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace sward;
using namespace sward::test;

namespace {

// A felled plant: its dynamic record differs from rest.
gpu::PlantDynamic felled() {
    return encodePlantDynamic(PlantMotion{.bend = {0.9f, 0.0f}, .state = gpu::kPlantStateFelled});
}

VegetationTile touchedTile() {
    VegetationTile tile = smallTile();
    tile.fields[1].dynamicRecords[5] = felled();
    tile.fields[3].active = true;
    tile.fields[3].timeStamp = 17;
    return tile;
}

} // namespace

TEST(TileState, OnlyTouchedFieldsAreKept) {
    const VegetationTile tile = touchedTile();
    const TileInteractionState state = captureTouchedFields(tile);
    ASSERT_EQ(state.fields.size(), 2u);
    EXPECT_EQ(state.fields[0].field, 1u);
    EXPECT_EQ(state.fields[1].field, 3u);
    EXPECT_TRUE(state.fields[1].active);
    EXPECT_EQ(state.fields[1].lastContactTick, 17u);
    EXPECT_LT(state.bytes(), countVegetation(tile).dynamicBytes);
    EXPECT_TRUE(captureTouchedFields(smallTile()).fields.empty());
}

TEST(TileState, RestoringIntoAFreshTileGivesBackTheTouchedTileBitwise) {
    const VegetationTile touched = touchedTile();
    VegetationTile fresh = smallTile();
    restoreTouchedFields(fresh, captureTouchedFields(touched), "test");
    for (size_t f = 0; f < fresh.fields.size(); ++f) {
        EXPECT_TRUE(sameBytes(fresh.fields[f].dynamicRecords, touched.fields[f].dynamicRecords)) << f;
        EXPECT_EQ(fresh.fields[f].active, touched.fields[f].active);
        EXPECT_EQ(fresh.fields[f].timeStamp, touched.fields[f].timeStamp);
    }
    // Restoring an empty state resets what was touched.
    restoreTouchedFields(fresh, TileInteractionState{}, "test");
    EXPECT_TRUE(captureTouchedFields(fresh).fields.empty());
}

TEST(TileState, AStateOfAnotherTileIsRefusedAndChangesNothing) {
    TileInteractionState state = captureTouchedFields(touchedTile());
    state.fields[0].dynamics.pop_back();
    VegetationTile tile = smallTile();
    EXPECT_NE(errorOf([&] { restoreTouchedFields(tile, state, "w.state"); }).find("another seed"), std::string::npos);
    EXPECT_TRUE(captureTouchedFields(tile).fields.empty());
}

TEST(WorldStateFile, SavesAndLoadsBitwise) {
    WorldInteractionState state{.tick = 99, .tilesX = 16, .tilesY = 16};
    TileInteractionState a = captureTouchedFields(touchedTile()), b = a;
    a.coord = {3, 5};
    b.coord = {0, 6};
    state.tiles = {a, b};
    const std::string path = (tempDir() / "world.state").string();
    saveWorldState(path, state);
    const WorldInteractionState back = loadWorldState(path, 0);
    EXPECT_EQ(back.tick, 99u);
    EXPECT_EQ(back.tilesX, 16u);
    ASSERT_EQ(back.tiles.size(), 2u);
    EXPECT_EQ(back.tiles[1].coord, (TileCoord{0, 6}));
    ASSERT_EQ(back.tiles[0].fields.size(), a.fields.size());
    for (size_t f = 0; f < a.fields.size(); ++f) {
        EXPECT_EQ(back.tiles[0].fields[f].field, a.fields[f].field);
        EXPECT_TRUE(sameBytes(back.tiles[0].fields[f].dynamics, a.fields[f].dynamics));
    }
}

TEST(WorldStateFile, AStateOfAnotherSeedIsRefusedAtLoadNamingBothSeeds) {
    WorldInteractionState state{.tick = 1, .tilesX = 2, .tilesY = 2, .seed = 5};
    state.tiles = {captureTouchedFields(touchedTile())};
    const std::string path = (tempDir() / "world.state").string();
    saveWorldState(path, state);
    EXPECT_EQ(loadWorldState(path, 5).seed, 5u);
    EXPECT_EQ(errorOf([&] { loadWorldState(path, 6); }),
              path + ": the world state was saved from a world of seed 5; this scene's seed is 6");
}

TEST(WorldStateFile, CorruptFilesAreRefusedNamingTheFile) {
    WorldInteractionState state{.tick = 1, .tilesX = 2, .tilesY = 2};
    state.tiles = {captureTouchedFields(touchedTile())};
    const std::string path = (tempDir() / "world.state").string();
    saveWorldState(path, state);
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto write = [&](const std::string& b) { std::ofstream(path, std::ios::binary | std::ios::trunc) << b; };
    std::string flipped = bytes;
    flipped[40] ^= 1;
    write(flipped);
    EXPECT_NE(errorOf([&] { loadWorldState(path, 0); }).find("checksum mismatch"), std::string::npos);
    write(bytes.substr(0, 20));
    EXPECT_NE(errorOf([&] { loadWorldState(path, 0); }).find("truncated"), std::string::npos);
    write("SWARDST1" + bytes.substr(8));
    EXPECT_NE(errorOf([&] { loadWorldState(path, 0); }).find("wrong magic (expected SWARDWS1)"), std::string::npos);
    std::filesystem::remove(path);
    EXPECT_NE(errorOf([&] { loadWorldState(path, 0); }).find(path + ": cannot open the world state file"),
              std::string::npos);
}

// A world's ruts ride in the world state (version 3); a world without ruts writes version 2, its bytes as before.
TEST(WorldStateFile, RutsAreSavedAsVersion3AndAWorldWithoutThemStaysVersion2) {
    WorldInteractionState state{.tick = 7, .tilesX = 2, .tilesY = 2};
    state.tiles = {captureTouchedFields(touchedTile())};
    const std::string path = (tempDir() / "world.state").string();
    auto version = [&] {
        std::ifstream in(path, std::ios::binary);
        in.seekg(8);
        uint32_t v = 0;
        in.read(reinterpret_cast<char*>(&v), sizeof v);
        return v;
    };
    saveWorldState(path, state);
    EXPECT_EQ(version(), 2u);
    EXPECT_TRUE(loadWorldState(path, 0).tracks.empty());
    TrackBlock block(gpu::kTrackBlockCells * gpu::kTrackBlockCells, 0.0f);
    block[33] = 0.04f;
    state.tracks = {{TrackBlockKey{-3, 2}, block}, {TrackBlockKey{5, 2}, block}};
    saveWorldState(path, state);
    EXPECT_EQ(version(), 3u);
    const WorldInteractionState back = loadWorldState(path, 0);
    EXPECT_EQ(back.tracks, state.tracks);
    ASSERT_EQ(back.tiles.size(), 1u);
    EXPECT_EQ(back.tiles[0].fields.size(), state.tiles[0].fields.size());
}
