// Interaction state files: save, restore, corrupt files. CPU only.
#include "test_files.h"
#include "interaction_world.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

using namespace sward;
using namespace sward::test;

TEST(StateFile, SaveRestoreContinueIsBitwiseIdenticalToAnUninterruptedRun) {
    const VegetationTile& tile = smallTile();
    const std::string path = (tempDir() / "state.bin").string();
    auto collidersAt = [](uint32_t t) {
        std::vector<Collider> c = makeGusts(2, 10, {{0, 0, 0.0f}, {50, 50, 0.4f}}, t);
        c.push_back(makeCapsule(1, {3.0f + 0.3f * t, 40, 0.4f}, {3.0f + 0.3f * t, 40.3f, 0.4f}, 0.4f, 3.0f));
        c.push_back(makeMower(makeSphere(2, {45, 3.0f + 0.3f * t, 0.2f}, 0.5f, 0.2f), 0.1f));
        return c;
    };
    Sim straight = makeSim(tile), first = makeSim(tile);
    for (uint32_t t = 0; t < 60; ++t) {
        auto c = collidersAt(t);
        straight.step(c);
        first.step(c);
    }
    first.world.saveState(path, first.dynamics, {});
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

    Sim resumed = makeSim(tile);
    resumed.dynamics = resumed.world.restoreState(path).dynamics;
    EXPECT_EQ(resumed.world.tick(), 60u);
    EXPECT_EQ(resumed.world.activeFields(), straight.world.activeFields());
    for (uint32_t t = 60; t < 150; ++t) {
        auto c = collidersAt(t);
        TickResult a = straight.step(c), b = resumed.step(c);
        ASSERT_TRUE(sameBytes(a.contacts, b.contacts));
        ASSERT_EQ(a.activeFields, b.activeFields);
    }
    EXPECT_TRUE(sameBytes(straight.dynamics, resumed.dynamics));
    EXPECT_EQ(straight.world.tick(), resumed.world.tick());
}

TEST(StateFile, CorruptTruncatedOrForeignFilesAreErrorsNamingTheFile) {
    const VegetationTile& tile = smallTile();
    const auto dir = tempDir();
    const std::string path = (dir / "state.bin").string();
    InteractionWorld world(tile, tileParams(50), {});
    world.saveState(path, world.initialDynamics(), {});
    std::vector<char> good;
    {
        std::ifstream in(path, std::ios::binary);
        good.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    auto expectError = [&](const std::vector<char>& bytes, const std::string& needle) {
        const std::string bad = (dir / "bad.bin").string();
        {
            std::ofstream out(bad, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(bytes.size()));
        }
        try {
            world.restoreState(bad);
            ADD_FAILURE() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    auto flipped = good;
    flipped[good.size() / 2] ^= 0x10; // inside the dynamic records
    expectError(flipped, "checksum");
    expectError({good.begin(), good.end() - 100}, "truncated");
    auto longer = good;
    longer.insert(longer.end(), 16, '\0');
    expectError(longer, "size");
    expectError({good.begin(), good.begin() + 20}, "truncated");
    auto magic = good;
    magic[0] = 'X';
    expectError(magic, "magic");
    auto version = good;
    version[8] = 9;
    expectError(version, "version");
    try {
        world.restoreState((dir / "missing.bin").string());
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing.bin"), std::string::npos);
    }
    // A valid file of another tile is refused too.
    InteractionState other = loadInteractionState(path);
    other.dynamics.pop_back();
    saveInteractionState((dir / "other.bin").string(), other);
    EXPECT_THROW(world.restoreState((dir / "other.bin").string()), Error);
    EXPECT_EQ(world.tick(), 0u);
}

TEST(StateFile, AFileLongerThanAnyValidStateIsRefusedBeforeItIsRead) {
    const std::string path = (tempDir() / "huge.bin").string();
    { std::ofstream(path, std::ios::binary) << "SWARDST1"; }
    // Sparse: 4 GiB on paper. Reading it would allocate 4 GiB; the length alone decides.
    std::filesystem::resize_file(path, uint64_t(4) << 30);
    try {
        loadInteractionState(path);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": not a valid interaction state file: 4294967296 bytes, more than the "
                                                "largest valid state (409542692 bytes)");
    }
}
