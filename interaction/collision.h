// The CPU collision pass of paper 3.3 / issue 6: each fixed tick, colliders become per-plant contacts for the GPU.
//
// Colliders overlapping the tile's vegetation go into a BVH rebuilt every tick (Morton order with the rank as
// tie break, so the tree and every result are deterministic). Each field whose box meets a collider is visited, then
// only its clusters whose boxes meet one, then only the plants of the cluster's sub-cells under the collider's
// footprint (TileCollisionIndex: positions decoded once, bucketed in an 8x8 grid per cluster). A plant is its
// upright stem, the vertical segment from its base up by its full height; it is touched when the collider
// penetrates the stem point nearest to the collider's axis.
//
// Per touched plant and collider:
//   direction  horizontal, from the collider's axis point (axisPoint) to the stem point;
//   Push/Gust  bend = pushGain * force * depth / plantHeight, depth = penetration in metres;
//   Downwash   bend = pushGain * force * depth / radius (1 - distance / radius for a vertical column), times a
//              linear fall-off to half strength at the column's lower end;
//   Mower      as Push, and cut byte = round(255 * cutHeight / plantHeight) clamped to 0..254 (no cut when
//              cutHeight >= plantHeight);
//   Fell       a Push collider whose force exceeds the category's fellForce: push = direction * fellBend.
// Several colliders on one plant combine in collider id order (ties: input order): the pushes are summed in that
// order; Fell wins over Cut wins over Push; a Fell contact's push is the unit summed direction * fellBend (the first
// felling collider's direction when the sum vanishes); other pushes are clamped to magnitude 0.95; the cut byte is
// the smallest one. Output: at most one gpu::PlantContact per plant, sorted by plant index.
#pragma once

#include "interaction/colliders.h"
#include "interaction/recovery.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"

#include "shared/gpu_layout.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace sward {

// How the plants of one category respond to colliders.
struct CategoryInteraction {
    float fellForce = 0.6f; // a Push collider with a larger force flattens the plant for good (collider units)
    float pushGain = 2.0f;  // bend per unit of force * penetration / plant height
};

// Interaction configuration: per category responses (index = atlas row, as VegetationParams::categories) and the
// recovery spring. Defaults: ferns 1.0, grass 0.6, flowers 0.8, extra 0.8 fell force; push gain 2.
struct InteractionParams {
    std::array<CategoryInteraction, gpu::kMaxPlantCategories> categories = {
        CategoryInteraction{1.0f, 2.0f}, CategoryInteraction{0.6f, 2.0f}, CategoryInteraction{0.8f, 2.0f},
        CategoryInteraction{0.8f, 2.0f}};
    RecoveryParams recovery;
};

// Reads the scene file's "interaction" object (every key optional, unknown keys are errors):
//   categories  array of 1..4 objects {"fell_force": 0..1e6, "push_gain": 0..1000}; entry i sets category i
//   recovery    {"time_step": (0, 1], "stiffness": 0..1e6, "damping": 0..1e6, "rest_bend": 0..0.5,
//                "fell_bend": 0..0.95, "rest_ticks": 1..1e6}
// Throws sward::Error naming `source` and the offending key.
InteractionParams parseInteractionParams(const nlohmann::json& json, const std::string& source);

// Colliders in a linear bounding volume hierarchy (Morton order), rebuilt per tick. Ranks are positions in (id, input index) order.
class ColliderBvh {
public:
    // Keeps the colliders whose bounds overlap `keep` (the vegetation's bounds) and builds the tree over them.
    void build(std::span<const Collider> colliders, const Aabb& keep);
    // Appends the ranks of the kept colliders whose bounds overlap box, in ascending rank (= id) order.
    void query(const Aabb& box, std::vector<uint32_t>& ranks) const;

    uint32_t size() const { return uint32_t(input_.size()); }
    uint32_t inputIndex(uint32_t rank) const { return input_[rank]; } // index into build()'s span
    const Aabb& bounds(uint32_t rank) const { return bounds_[rank]; }

private:
    struct Node {
        Aabb box;
        uint32_t first = 0, count = 0; // leaf: items_[first, first + count); inner (count 0): children first, first+1
    };
    struct Kept {
        uint32_t id, input;
        Aabb box;
    };
    std::vector<Kept> kept_;                // scratch of build(), kept for its capacity
    std::vector<uint64_t> keys_, keysTmp_;  // likewise
    std::vector<uint32_t> input_; // rank -> input index
    std::vector<Aabb> bounds_;    // by rank
    std::vector<uint32_t> items_; // ranks in tree order
    std::vector<Node> nodes_;
    uint32_t root_ = 0;
};

// Plant positions and heights of a tile decoded once, bucketed per cluster into an 8x8 grid of sub-cells so a
// collider visits only the plants under its footprint. Built from the tile's static records; immutable.
// The pass is bound by memory latency (a worst-case tick reads thousands of scattered runs of a 64 MB index), so
// each plant is one 16-byte Stem (four per cache line) holding everything the tests need, and all stems and cell
// offsets live in one block backed by huge pages where the system allows (fewer TLB misses).
class TileCollisionIndex {
public:
    static constexpr uint32_t kCellsPerSide = 8;
    static constexpr uint32_t kMaxFieldPlants = 1u << 22;
    struct Stem {
        float x, y, z;  // base position (decodePlantPosition), metres
        uint32_t packed; // bits 0-21 plant index within the field's records, 22-23 category, 24-31 size byte
        uint32_t plant() const { return packed & (kMaxFieldPlants - 1); }
        uint32_t category() const { return (packed >> 22) & 3u; }
        uint32_t shape() const { return packed >> 22; } // category | size << 2: the index into heights()
    };
    struct Field {
        const Stem* stems = nullptr;         // by cluster, then cell (row-major, x fastest), then record index
        const uint32_t* cellStart = nullptr; // clusters * 64 + 1 offsets into stems
        uint32_t clustersWithPlants = 0;
        float overhang = 0.0f; // how far any cluster's box reaches beyond its square of the cluster grid, metres
    };

    TileCollisionIndex() = default;
    // Requires params to be the ones the tile was generated with (category heights). Throws sward::Error if a
    // field holds more than kMaxFieldPlants plants.
    TileCollisionIndex(const VegetationTile& tile, const VegetationParams& params);

    const Field& field(uint32_t f) const { return fields_[f]; }
    const Aabb& bounds() const { return bounds_; } // union of every field's bounds
    float cellSize() const { return cellSize_; }
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
    float cellSize_ = 0.0f;
};

struct CollisionStats {
    uint32_t colliders = 0;      // given
    uint32_t collidersKept = 0;  // overlapping the vegetation's bounds (inserted in the BVH)
    uint32_t fieldsTested = 0;   // fields whose box met at least one collider box
    uint32_t clustersTested = 0; // cluster boxes tested in those fields
    uint64_t plantsTested = 0;   // stems tested against a collider hull
    uint64_t contactBytes = 0;   // contacts * sizeof(gpu::PlantContact): the upload
    double cpuMs = 0.0;          // wall time of the pass (steady_clock; reported, never fed back into results)
    double buildMs = 0.0;        // of which building the BVH
};

struct CollisionResult {
    std::vector<gpu::PlantContact> contacts; // sorted by plant, at most one per plant
    std::vector<uint32_t> touchedFields;     // fields with contacts, ascending
    std::vector<uint32_t> touchedClusters;   // tile cluster indices (field.firstCluster + k) with contacts, ascending
    CollisionStats stats;
};

// Contact of one plant with one collider, before combination (exposed for tests and tools).
struct PlantTouch {
    glm::vec2 push{0.0f}; // horizontal tip offset, plant heights (unit direction * fellBend for Fell)
    uint32_t kind = 0;    // gpu::kContact*, 0 = no contact
    uint32_t cut = gpu::kPlantUncut;
};
// How collider c touches a plant standing at base with the given full height and category response.
PlantTouch touchPlant(const Collider& c, glm::vec3 base, float height, const CategoryInteraction& response,
                      const RecoveryParams& recovery);
// Combines the touches of one plant given in collider id order into its contact (rules above; plant/field unset).
gpu::PlantContact combineTouches(std::span<const PlantTouch> touches, const RecoveryParams& recovery);

// The collision pass. Owns the plant index, the BVH, per-field output slots and a persistent worker pool, so a
// tick neither allocates much nor starts threads; not thread-safe itself, but runs on `threads` threads inside and
// its result does not depend on the thread count (each field is collided by one thread into its own slot, and the
// slots are merged in field order).
class CollisionPass {
public:
    // tile must outlive the pass; vegetation are the params it was generated with. Builds the plant index.
    CollisionPass(const VegetationTile& tile, const VegetationParams& vegetation, const InteractionParams& params);
    ~CollisionPass();
    CollisionPass(CollisionPass&&) noexcept;
    CollisionPass& operator=(CollisionPass&&) noexcept;
    // Contacts of this tick; threads >= 1.
    CollisionResult run(std::span<const Collider> colliders, uint32_t threads);

private:
    struct FieldOutput {
        std::vector<gpu::PlantContact> contacts;
        std::vector<uint32_t> clusters;
        uint32_t clustersTested = 0;
        uint64_t plantsTested = 0;
        bool tested = false;
    };
    struct Scratch;
    class Workers;
    void collideField(uint32_t f, std::span<const Collider> colliders, Scratch& scratch, FieldOutput& out) const;

    const VegetationTile* tile_;
    TileCollisionIndex index_;
    InteractionParams params_;
    ColliderBvh bvh_;
    std::vector<FieldOutput> outputs_;
    std::vector<Scratch> scratch_;     // one per thread, kept between ticks
    std::unique_ptr<Workers> workers_; // threads - 1 helpers, started on first use
};

} // namespace sward
