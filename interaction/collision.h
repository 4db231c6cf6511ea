// The CPU collision pass of paper 3.3 / issue 6: each fixed tick, colliders become per-plant contacts for the GPU.
//
// Colliders overlapping the tile's vegetation are binned into the fields their boxes meet every tick (ColliderGrid:
// ranks in collider id order, so every result is deterministic). Each field whose box meets a collider is visited, then
// only its clusters whose boxes meet one, then only the plants of the cluster's sub-cells under the collider's
// footprint (TileCollisionIndex: positions decoded once, bucketed in a 32 x 8 grid per cluster). A plant is its
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
//   Fell       a Push collider whose force exceeds the category's fellForce, or whose bend exceeds its maxBend:
//              push = direction * fellBend.
// Several colliders on one plant combine in collider id order (ties: input order): the pushes are summed in that
// order; Fell wins over Cut wins over Push; a Fell contact's push is the unit summed direction * fellBend (the first
// felling collider's direction when the sum vanishes); other pushes are clamped to magnitude 0.95; the cut byte is
// the smallest one. Output: at most one gpu::PlantContact per plant, sorted by plant index.
#pragma once

#include "interaction/collider_grid.h"
#include "interaction/collision_index.h"
#include "interaction/interaction_params.h"
#include "interaction/tick_contacts.h"

#include "shared/gpu_layout.h"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace sward {

class ParallelFor;

struct CollisionStats {
    uint32_t colliders = 0;      // given
    uint32_t collidersKept = 0;  // overlapping the vegetation's bounds (binned into fields)
    uint32_t fieldsTested = 0;   // fields whose box met at least one collider box
    uint32_t clustersTested = 0; // cluster boxes tested in those fields
    uint64_t plantsTested = 0;   // stems tested against a collider hull
    uint64_t contactBytes = 0;   // contacts * sizeof(gpu::PlantContact): the upload
    double cpuMs = 0.0;          // wall time of the pass (steady_clock; reported, never fed back into results)
    double buildMs = 0.0;        // of which keeping and ranking the colliders (on the calling thread; their binning
                                 // into the fields runs on the pool, before the fields)
    double mergeMs = 0.0;        // and gathering the fields' results in field order (likewise)
};

struct CollisionResult {
    TickContacts contacts;                   // sorted by plant, at most one per plant: the fields' runs
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

// The collision pass. Owns the plant index, the collider grid, per-field output slots and a persistent worker pool,
// so a tick neither allocates much nor starts threads; not thread-safe itself, but runs on `threads` threads inside
// and its result does not depend on the thread count (each field is collided into its own slot,
// common/parallel_for.h, and the slots are gathered in field order; the contacts stay where the fields wrote them).
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
        uint32_t contactCount = 0; // in the field's buffer of the set being written (ContactBuffers)
        std::vector<uint32_t> clusters;
        uint32_t clustersTested = 0;
        uint64_t plantsTested = 0;
        bool tested = false;
    };
    // A row of sub-cells under one collider's footprint in one cluster: stems [begin, end) to test.
    struct Run {
        uint32_t rank, begin, end;
    };
    // Per field, room for its contacts, never zero-filled: writing them through a vector's emplace_back (capacity
    // check, size update reloaded after every store) was a sixth of emitting them. A tick's TickContacts shares the
    // set its fields wrote: run() writes into a set no result holds, so the contacts a caller keeps never change.
    struct ContactBuffers {
        explicit ContactBuffers(size_t fields) : field(fields), room(fields, 0) {}
        std::vector<std::unique_ptr<gpu::PlantContact[]>> field;
        std::vector<uint32_t> room;
    };
    struct Scratch;
    // The steps of one field's collision, in order (collision.cpp tells how each keeps the result deterministic).
    bool prepareField(uint32_t f, Scratch& scratch, uint32_t buffer, FieldOutput& out) const;
    void finishField(uint32_t f, std::span<const Collider> colliders, Scratch& scratch, uint32_t buffer,
                     FieldOutput& out) const;
    void findCellRuns(uint32_t f, const TileCollisionIndex::Field& index, std::vector<Run>& runs) const;
    PlantTouch touchStem(const Collider& c, const Aabb& box, const TileCollisionIndex::Stem& stem) const;
    uint64_t touchStems(const TileCollisionIndex::Field& index, uint32_t plantCount,
                        std::span<const Collider> colliders, std::span<const Run> runs, Scratch& s) const;
    void emitContacts(uint32_t f, const FieldVegetation& field, Scratch& s, FieldOutput& out) const;
    void collideFields(std::span<const Collider> colliders);
    CollisionResult gatherFields(std::span<const Collider> colliders) const;
    void takeFreeBuffers();

    const VegetationTile* tile_;
    TileCollisionIndex index_;
    InteractionParams params_;
    ColliderGrid grid_;
    std::vector<FieldOutput> outputs_;
    // Sets of contact buffers kept for their room: the one being written (writing_), and one more while a caller
    // keeps the previous tick's contacts (as sward's simulations do until the next tick).
    std::vector<std::shared_ptr<ContactBuffers>> buffers_;
    std::shared_ptr<ContactBuffers> writing_;
    std::vector<Scratch> scratch_;      // one per thread, kept between ticks
    std::unique_ptr<ParallelFor> pool_; // threads - 1 helpers, started on first use
};

} // namespace sward
