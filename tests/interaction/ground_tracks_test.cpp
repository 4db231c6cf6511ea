// Ground tracks (interaction/ground_tracks.h): ruts of the configured depth, continuous however fast the wheel,
// treads, independent of collider order, patch edges that meet the unpressed ground, and the state file round trip.
#include "interaction/ground_tracks.h"
#include "interaction/state_file.h"

#include "common/error.h"
#include "shared/gpu_layout.h"
#include "world/ground.h"

#include <gtest/gtest.h>
#include <map>
#include <set>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace sward;

namespace {

constexpr float kRut = 0.04f, kRadius = 0.16f, kHalfWidth = 0.06f;

// A gently sloped plane (z = 0.05 x + 0.02 y), 40 x 40 m from the origin: the rut follows the ground.
Ground slopedGround() {
    const uint32_t n = 21;
    std::vector<float> heights(n * n);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) heights[j * n + i] = 0.05f * 2.0f * float(i) + 0.02f * 2.0f * float(j);
    return Ground(Heightfield(n, n, 2.0f, glm::vec2(0.0f), std::move(heights)));
}

// A wheel (capsule along x) resting on the ground at (x, y), pressing ruts of kRut.
Collider wheelAt(const Ground& ground, uint32_t id, float x, float y, RutParams rut = {kRut, 0.0f, 0.0f}) {
    const float z = ground.height(glm::vec2(x, y)) + kRadius;
    Collider c = makeCapsule(id, {x - kHalfWidth, y, z}, {x + kHalfWidth, y, z}, kRadius, 2.0f);
    c.rut = rut;
    return c;
}

int64_t lattice(float metres) {
    return int64_t(std::lround(metres / gpu::kTrackCell));
}

// Drives wheels along +y from y0 in steps of `step` metres for `ticks` ticks (previous tick swept to this one).
GroundTracks drive(const Ground& ground, std::vector<float> xs, float y0, float step, int ticks, RutParams rut,
                   bool reversed = false) {
    GroundTracks tracks;
    std::vector<Collider> previous;
    for (int t = 0; t < ticks; ++t) {
        std::vector<Collider> now;
        for (size_t k = 0; k < xs.size(); ++k)
            now.push_back(wheelAt(ground, uint32_t(k), xs[k], y0 + step * float(t), rut));
        if (reversed) std::reverse(now.begin(), now.end());
        tracks.press(previous, now, ground);
        previous = now;
    }
    return tracks;
}

} // namespace

TEST(GroundTracks, AFastWheelLeavesAContinuousRutOfItsDepthFollowingTheGround) {
    const Ground ground = slopedGround();
    // 0.4 m per tick: a wheel print is 0.23 m long, so unswept prints would leave humps 2.5 cm high between them.
    const GroundTracks tracks = drive(ground, {10.0f}, 10.0f, 0.4f, 21, {kRut, 0.0f, 0.0f});
    float shallowest = 1.0f;
    for (int64_t j = lattice(10.0f); j <= lattice(18.0f); ++j)
        shallowest = std::min(shallowest, tracks.depth(lattice(10.0f), j));
    EXPECT_GT(shallowest, kRut - 2e-4f) << "the rut is not continuous along the wheel's path";
    EXPECT_LE(shallowest, kRut);
    // Across the track: full depth under the tyre, none beyond its rounded edge (half width + sqrt(2 r depth)).
    const int64_t j = lattice(14.0f);
    EXPECT_FLOAT_EQ(tracks.depth(lattice(10.0f + kHalfWidth), j), kRut);
    EXPECT_EQ(tracks.depth(lattice(10.0f + kHalfWidth + 0.15f), j), 0.0f);
    EXPECT_EQ(tracks.depth(lattice(10.0f - kHalfWidth - 0.15f), j), 0.0f);
    // Nothing ahead of where the wheel stopped (y = 18 m) beyond its print.
    EXPECT_EQ(tracks.depth(lattice(10.0f), lattice(18.2f)), 0.0f);
}

TEST(GroundTracks, TreadsRaiseTheFloorInWornJitteredGroovesAcrossTheDirectionOfTravel) {
    const Ground ground = slopedGround();
    const RutParams rut{kRut, 0.1f, 0.015f};
    const GroundTracks tracks = drive(ground, {10.0f}, 10.0f, 0.13f, 40, rut);
    // Walk the rut's centre line lug by lug (lug k spans y in [k, k + 1) pitches): each lug's floor is the full rut,
    // then a groove raises it by a share of the tread depth that is the lug's own.
    std::map<int64_t, std::pair<uint32_t, uint32_t>> perLug; // lug -> (floor vertices, groove vertices)
    std::set<int32_t> wear;                                  // groove raises in 0.1 mm
    for (int64_t j = lattice(11.0f); j < lattice(14.0f); ++j) {
        const float d = tracks.depth(lattice(10.0f), j);
        const int64_t lug = int64_t(std::floor(trackVertexPosition(lattice(10.0f), j).y / rut.treadPitch));
        if (std::abs(d - kRut) < 2e-4f) {
            ++perLug[lug].first;
            continue;
        }
        const float raise = kRut - d;
        EXPECT_GE(raise, 0.4f * rut.treadDepth - 2e-4f) << "at y = " << float(j) * gpu::kTrackCell;
        EXPECT_LE(raise, rut.treadDepth + 2e-4f) << "at y = " << float(j) * gpu::kTrackCell;
        ++perLug[lug].second;
        wear.insert(int32_t(std::lround(raise * 1e4f)));
    }
    uint32_t lugs = 0, minGroove = 1000, maxGroove = 0;
    for (const auto& [lug, counts] : perLug) {
        if (counts.first + counts.second < 4) continue; // a lug cut by the walk's ends
        ++lugs;
        EXPECT_GT(counts.first, 0u) << "lug " << lug << " has no floor";
        EXPECT_GT(counts.second, 0u) << "lug " << lug << " has no groove";
        minGroove = std::min(minGroove, counts.second);
        maxGroove = std::max(maxGroove, counts.second);
    }
    EXPECT_GT(lugs, 25u);
    EXPECT_GT(maxGroove, minGroove) << "every groove the same length: no jitter";
    EXPECT_GT(wear.size(), 10u) << "every groove the same depth: no wear";
}

TEST(GroundTracks, DepthsAreTheSameWhateverTheOrderOfTheColliders) {
    const Ground ground = slopedGround();
    const RutParams rut{kRut, 0.1f, 0.01f};
    // Two wheels whose ruts overlap: the deeper one wins wherever they meet, in any order.
    const GroundTracks a = drive(ground, {10.0f, 10.2f}, 10.0f, 0.3f, 12, rut);
    const GroundTracks b = drive(ground, {10.0f, 10.2f}, 10.0f, 0.3f, 12, rut, true);
    ASSERT_EQ(a.blocks().size(), b.blocks().size());
    for (const auto& [key, block] : a.blocks()) {
        ASSERT_TRUE(b.blocks().count(key));
        EXPECT_EQ(std::memcmp(block.data(), b.blocks().at(key).data(), block.size() * sizeof(float)), 0);
    }
}

TEST(GroundTracks, APatchMeetsTheUnpressedGroundWithUnpressedVertices) {
    const Ground ground = slopedGround();
    // Crossing block borders in both axes (blocks are 0.8 m): x = 9.6 m is one.
    const GroundTracks tracks = drive(ground, {9.6f, 12.0f}, 9.5f, 0.2f, 20, {kRut, 0.0f, 0.0f});
    const int64_t n = gpu::kTrackBlockCells;
    ASSERT_GT(tracks.blocks().size(), 8u);
    auto drawn = [&](int32_t x, int32_t y) { return tracks.blocks().count({x, y}) != 0; };
    uint64_t edgeVertices = 0;
    for (const auto& [key, block] : tracks.blocks()) {
        const int64_t i0 = int64_t(key.x) * n, j0 = int64_t(key.y) * n;
        // Where a neighbour is not drawn, the patch's edge towards it and its ring beyond lie on the unpressed
        // ground (the coarse ground drawn there meets them).
        for (int64_t k = 0; k <= n; ++k)
            for (int64_t r = 0; r <= int64_t(gpu::kTrackPatchRing); ++r) { // the edge, then the ring beyond it
                const bool right = drawn(key.x + 1, key.y) || tracks.depth(i0 + n + r, j0 + k) == 0.0f;
                const bool left = drawn(key.x - 1, key.y) || tracks.depth(i0 - r, j0 + k) == 0.0f;
                const bool up = drawn(key.x, key.y + 1) || tracks.depth(i0 + k, j0 + n + r) == 0.0f;
                const bool down = drawn(key.x, key.y - 1) || tracks.depth(i0 + k, j0 - r) == 0.0f;
                edgeVertices += right && left && up && down ? 1 : 1000000;
            }
    }
    EXPECT_LT(edgeVertices, 1000000u) << "a pressed vertex on the edge towards a block that is not drawn";
    EXPECT_GT(edgeVertices, 0u);
}

TEST(GroundTracks, RevisionsTellWhichBlocksChanged) {
    const Ground ground = slopedGround();
    GroundTracks tracks;
    const Collider wheel = wheelAt(ground, 1, 10.0f, 10.0f);
    tracks.press({}, std::vector{wheel}, ground);
    const uint64_t first = tracks.revision();
    EXPECT_GT(first, 0u);
    tracks.press({}, std::vector{wheel}, ground); // the same print again: nothing changes
    EXPECT_EQ(tracks.revision(), first);
    tracks.press(std::vector{wheel}, std::vector{wheelAt(ground, 1, 10.0f, 12.0f)}, ground);
    EXPECT_GT(tracks.revision(), first);
    EXPECT_EQ(tracks.blockRevision({trackBlockOf(lattice(10.0f)), trackBlockOf(lattice(12.0f))}), tracks.revision());
    EXPECT_EQ(tracks.blockRevision({100, 100}), 0u);
}

TEST(GroundTracks, SurviveTheStateFileBitwiseAndBadDepthsAreRefused) {
    const Ground ground = slopedGround();
    const GroundTracks tracks = drive(ground, {10.0f}, 10.0f, 0.3f, 10, {kRut, 0.1f, 0.01f});
    const auto dir = std::filesystem::temp_directory_path() / ("sward-tracks-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "state.bin").string();
    saveInteractionState(path, InteractionState{.tick = 10, .tracks = tracks.blocks()});
    const InteractionState loaded = loadInteractionState(path);
    EXPECT_EQ(loaded.tick, 10u);
    ASSERT_EQ(loaded.tracks.size(), tracks.blocks().size());
    for (const auto& [key, block] : tracks.blocks())
        EXPECT_EQ(std::memcmp(block.data(), loaded.tracks.at(key).data(), block.size() * sizeof(float)), 0);
    GroundTracks restored;
    restored.restore(loaded.tracks);
    EXPECT_EQ(restored.depth(lattice(10.0f), lattice(11.0f)), tracks.depth(lattice(10.0f), lattice(11.0f)));

    // A rut depth that is not a number, with a checksum that matches: refused, naming the file and the block.
    std::vector<char> bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const size_t firstDepth = 8 + 4 + 4 + 8 + 8 + 4 + 8; // header, block count, block key
    const float nan = std::nanf("");
    std::memcpy(bytes.data() + firstDepth, &nan, sizeof nan);
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t k = 0; k + 8 < bytes.size(); ++k) h = (h ^ uint8_t(bytes[k])) * 0x100000001b3ull;
    std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
    const std::string bad = (dir / "bad.bin").string();
    std::ofstream(bad, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    try {
        loadInteractionState(bad);
        FAIL() << "a NaN rut depth was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("track block 0"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}
