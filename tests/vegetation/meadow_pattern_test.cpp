// Issue 47: a meadow, not tufts. vegetation.pattern gathers plants into patches (with bare spots), tussocks and
// taller and shorter stretches, reproducibly and without seams; with every strength 0 placement is the map alone.
#include "vegetation/meadow_pattern.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"
#include "vegetation/vegetation_params.h"

#include "common/error.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace sward;

namespace {

// Uniform grass at 16 plants/m^2 on a flat 100 x 100 m tile.
VegetationParams grassParams(MeadowPattern pattern) {
    VegetationParams p;
    p.tileSize = 100.0f;
    p.seed = 11;
    p.pattern = pattern;
    return p;
}

const GrassMap& uniformGrass() {
    static const GrassMap map(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    return map;
}

// Flat ground under tiles (0, 0) and (1, 0).
const Ground& flat() {
    static const Ground ground(Heightfield(3, 2, 100.0f, glm::vec2(0.0f), {0, 0, 0, 0, 0, 0}));
    return ground;
}

struct Plant {
    glm::vec3 position;
    uint32_t size;
};

std::vector<Plant> plants(const VegetationParams& p, TileCoord tile = {}, uint32_t threads = 2) {
    const VegetationTile t = generateTile(flat(), uniformGrass(), p, tile, threads);
    std::vector<Plant> out;
    for (const FieldVegetation& field : t.fields)
        for (const gpu::PlantStatic& record : field.staticRecords)
            out.push_back(
                {decodePlantPosition(record, field.origin, field.positionStep), decodePlantStatic(record).size});
    return out;
}

// Plant counts in the 1 m cells of the tile at `origin`.
std::vector<uint32_t> cellCounts(const std::vector<Plant>& list, glm::vec2 origin) {
    std::vector<uint32_t> cells(100 * 100, 0);
    for (const Plant& plant : list) {
        const int x = std::clamp(int(plant.position.x - origin.x), 0, 99);
        const int y = std::clamp(int(plant.position.y - origin.y), 0, 99);
        ++cells[size_t(y) * 100 + size_t(x)];
    }
    return cells;
}

double coefficientOfVariation(const std::vector<uint32_t>& cells) {
    double sum = 0.0, squares = 0.0;
    for (uint32_t c : cells) sum += c, squares += double(c) * c;
    const double mean = sum / double(cells.size());
    return std::sqrt(squares / double(cells.size()) - mean * mean) / mean;
}

// Mean distance from each plant of the tile's middle 20 x 20 m to its nearest neighbour (plants bucketed by metre).
double meanNearestNeighbour(const std::vector<Plant>& list) {
    std::vector<std::vector<glm::vec2>> buckets(100 * 100);
    for (const Plant& plant : list)
        buckets[size_t(std::clamp(int(plant.position.y), 0, 99)) * 100 +
                size_t(std::clamp(int(plant.position.x), 0, 99))]
            .push_back(glm::vec2(plant.position));
    double sum = 0.0;
    uint32_t count = 0;
    for (int y = 40; y < 60; ++y)
        for (int x = 40; x < 60; ++x)
            for (glm::vec2 p : buckets[size_t(y) * 100 + size_t(x)]) {
                float best = 1e9f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        for (glm::vec2 q : buckets[size_t(y + dy) * 100 + size_t(x + dx)])
                            if (q != p) best = std::min(best, glm::length(q - p));
                sum += best;
                ++count;
            }
    return sum / count;
}

} // namespace

TEST(MeadowPattern, ZeroStrengthsLeaveThePlacementByteForByte) {
    MeadowPattern other;
    other.patchSize = 31.0f;
    other.clumpSize = 1.7f;
    const VegetationTile a = generateTile(flat(), uniformGrass(), grassParams({}), {}, 2);
    const VegetationTile b = generateTile(flat(), uniformGrass(), grassParams(other), {}, 2);
    ASSERT_EQ(a.fields.size(), b.fields.size());
    for (size_t i = 0; i < a.fields.size(); ++i) {
        const auto& x = a.fields[i].staticRecords;
        const auto& y = b.fields[i].staticRecords;
        ASSERT_EQ(x.size(), y.size());
        ASSERT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])), 0);
    }
}

TEST(MeadowPattern, PatchesVaryTheDensityDownToBareSpotsAndKeepTheMean) {
    // Stratified placement keeps every 1 m cell near 16 plants (coefficient of variation ~0.1); patches spread the
    // counts over a wide range, with bare cells, while the tile's total stays near the map's (the factor's mean is
    // 1 but for the clipping at 0).
    const std::vector<uint32_t> uniform = cellCounts(plants(grassParams({})), {});
    const std::vector<uint32_t> patchy = cellCounts(plants(grassParams({.patchSize = 8.0f, .patchiness = 0.8f})), {});
    EXPECT_LT(coefficientOfVariation(uniform), 0.15);
    EXPECT_GT(coefficientOfVariation(patchy), 0.5);
    EXPECT_GT(std::count(patchy.begin(), patchy.end(), 0u), 100);
    EXPECT_GT(*std::max_element(patchy.begin(), patchy.end()), 30u);
    double a = 0.0, b = 0.0;
    for (uint32_t c : uniform) a += c;
    for (uint32_t c : patchy) b += c;
    EXPECT_NEAR(b / a, 1.0, 0.15);
}

TEST(MeadowPattern, ClumpingGathersPlantsIntoTussocks) {
    // Clark and Evans: the mean nearest-neighbour distance of a random pattern of density d is 0.5 / sqrt(d)
    // (0.125 m at 16 / m^2); stratified jitter measures 0.096 m here. Tussocks of 0.6 m hold about 6 plants each,
    // pulled 70 % of the way to their centre: their neighbours are much closer.
    const double uniform = meanNearestNeighbour(plants(grassParams({})));
    const double clumped = meanNearestNeighbour(plants(grassParams({.clumping = 0.7f, .clumpSize = 0.6f})));
    EXPECT_GT(uniform, 0.08);
    EXPECT_LT(clumped, 0.6 * uniform);
}

TEST(MeadowPattern, PlantsStandTallerWhereTheyGrowDenser) {
    const MeadowPattern pattern{.patchSize = 8.0f, .patchiness = 0.6f, .heightGradient = 0.4f};
    const VegetationParams p = grassParams(pattern);
    const std::vector<Plant> list = plants(p);
    double dense = 0.0, sparse = 0.0;
    uint32_t denseCount = 0, sparseCount = 0;
    for (const Plant& plant : list) {
        const double n = patchNoise(pattern, p.seed, 1, plant.position.x, plant.position.y);
        if (n > 0.65) dense += plant.size, ++denseCount;
        if (n < 0.35) sparse += plant.size, ++sparseCount;
    }
    ASSERT_GT(denseCount, 1000u);
    ASSERT_GT(sparseCount, 100u);
    EXPECT_GT(dense / denseCount, 1.15 * (sparse / sparseCount));
}

TEST(MeadowPattern, IsTheSameForAnyThreadCountAndContinuesAcrossATileBorder) {
    const MeadowPattern pattern{.patchiness = 0.8f, .heightGradient = 0.3f, .clumping = 0.6f};
    const VegetationParams p = grassParams(pattern);
    const std::vector<Plant> one = plants(p, {}, 1), two = plants(p, {}, 2);
    ASSERT_EQ(one.size(), two.size());
    for (size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i].position, two[i].position);
    // The pattern is a function of the world position: the 2 m strips either side of the border between tiles
    // (0, 0) and (1, 0) hold about as many plants as each other.
    const std::vector<Plant> east = plants(p, {1, 0});
    auto strip = [](const std::vector<Plant>& list, float x0, float x1) {
        return std::count_if(list.begin(), list.end(),
                             [&](const Plant& q) { return q.position.x >= x0 && q.position.x < x1; });
    };
    const double west = double(strip(one, 98.0f, 100.0f)), eastSide = double(strip(east, 100.0f, 102.0f));
    EXPECT_NEAR(eastSide / west, 1.0, 0.2);
}

TEST(MeadowPattern, SceneKeysAreReadAndCheckedByName) {
    const VegetationParams p = parseVegetationParams(
        nlohmann::json::parse(R"({"pattern": {"patch_size": 12, "patchiness": 0.5, "height_gradient": 0.2,
                        "clumping": 0.4, "clump_size": 0.25}})"),
        "meadow.json");
    EXPECT_FLOAT_EQ(p.pattern.patchSize, 12.0f);
    EXPECT_FLOAT_EQ(p.pattern.patchiness, 0.5f);
    EXPECT_FLOAT_EQ(p.pattern.heightGradient, 0.2f);
    EXPECT_FLOAT_EQ(p.pattern.clumping, 0.4f);
    EXPECT_FLOAT_EQ(p.pattern.clumpSize, 0.25f);
    try {
        parseVegetationParams(nlohmann::json::parse(R"({"pattern": {"clumping": 2}})"), "meadow.json");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vegetation.pattern.clumping"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parseVegetationParams(nlohmann::json::parse(R"({"pattern": {"clumps": 1}})"), "meadow.json"), Error);
}
