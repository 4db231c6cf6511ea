// The plants of a tile as the collision pass reads them: decoded once, bucketed per cluster and sub-cell.
#pragma once

#include "interaction/colliders.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace sward {

// Plant positions and heights of a tile decoded once, bucketed per cluster into a grid of sub-cells so a collider
// visits only the plants under its footprint. Built from the tile's static records; immutable.
// The pass is bound by memory latency (a worst-case tick reads thousands of scattered runs of a 64 MB index), so
// each plant is one 16-byte Stem (four per cache line) holding everything the tests need, and all stems and cell
// offsets live in one block backed by huge pages where the system allows (fewer TLB misses).
class TileCollisionIndex {
public:
    // Sub-cells per cluster: kCellsX columns by kCellsY rows (0.16 x 0.63 m in 5 m clusters). A collider's plants
    // are read as one run of stems per row of sub-cells under its footprint: each row is a run to set up and fetch,
    // while narrower columns only trim the runs' ends. On 400 x 25 colliders of 0.5 m, 32 x 8 tests a third fewer
    // stems than 8 x 8 (7 % fewer instructions, 6 % faster); 16 x 16 makes more runs than it saves stems, and
    // 64 x 8 (8 % fewer stems again, offsets of 20 MB for a full tile) was slower (docs/benchmarks.md).
    static constexpr uint32_t kCellsX = 32, kCellsY = 8;
    static constexpr uint32_t kMaxFieldPlants = 1u << 22;
    // Zero stems after the last field's, so the pass may read groups of four stems past the end of any run.
    static constexpr uint32_t kPaddingStems = 3;
    struct Stem {
        float x, y, z;  // base position (decodePlantPosition), metres
        uint32_t packed; // bits 0-21 plant index within the field's records, 22-23 category, 24-31 size byte
        uint32_t plant() const { return packed & (kMaxFieldPlants - 1); }
        uint32_t category() const { return (packed >> 22) & 3u; }
        uint32_t shape() const { return packed >> 22; } // category | size << 2: the index into heights()
    };
    struct Field {
        const Stem* stems = nullptr;         // by cluster, then cell (row-major, x fastest), then record index
        const uint32_t* cellStart = nullptr; // clusters * kCellsX * kCellsY + 1 offsets into stems
        uint32_t clustersWithPlants = 0;
        float overhang = 0.0f; // how far any cluster's box reaches beyond its square of the cluster grid, metres
    };

    TileCollisionIndex() = default;
    // Requires params to be the ones the tile was generated with (category heights). Throws sward::Error if a
    // field holds more than kMaxFieldPlants plants.
    TileCollisionIndex(const VegetationTile& tile, const VegetationParams& params);

    const Field& field(uint32_t f) const { return fields_[f]; }
    const Aabb& bounds() const { return bounds_; } // union of every field's bounds
    glm::vec2 cellSize() const { return cellSize_; } // of a sub-cell, metres
    // Full plant height in metres by Stem::shape(): the same expression as placement's cluster bounds.
    const float* heights() const { return heights_.data(); }

private:
    struct Free {
        void operator()(void* p) const;
    };
    std::unique_ptr<Stem[], Free> stems_;
    std::vector<Field> fields_;
    std::array<float, 4 * 256> heights_{};
    Aabb bounds_;
    glm::vec2 cellSize_{0.0f};
};

} // namespace sward
