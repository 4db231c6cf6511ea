// InteractionWorld: the CPU side of plant interaction per fixed tick (paper 3.3-3.4, issue 6).
//
// Each step() runs the collision pass (collision.h) for the current tick and keeps the per-field bookkeeping the
// GPU dispatch needs: a field touched at tick t becomes active with last contact t; it stays active while
// t_now - lastContact < RecoveryParams::restTicks, so the recovery pass runs on it for restTicks ticks after its
// last contact (the contact tick included), then it is dropped and costs nothing. Untouched fields are never active.
// The GPU (or simulateOnCpu) then applies the tick's contacts and integrates every plant of every active field.
#pragma once

#include "interaction/collision.h"
#include "interaction/state_file.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

struct TickResult : CollisionResult {
    uint64_t tick = 0;                  // the tick these contacts belong to
    std::vector<uint32_t> activeFields; // fields to run recovery on this tick (after this tick's contacts), ascending
};

class InteractionWorld {
public:
    // tile must outlive the world and have its fields packed in field order (generateTile); vegetation are the
    // params it was generated with. threads >= 1; results do not depend on it.
    InteractionWorld(const VegetationTile& tile, const VegetationParams& vegetation, const InteractionParams& params,
                     uint32_t threads = 1);

    // Collides the colliders at the current tick, updates field activity and advances the tick.
    TickResult step(std::span<const Collider> colliders);

    // Continues a tile that was simulated before (a world tile made resident again, or its simulation made anew):
    // the next tick is `tick` and field activity is the tile's FieldVegetation::active / timeStamp.
    void resumeAt(uint64_t tick);
    // Writes field activity into `tile` (FieldVegetation::active / timeStamp; the tile this world was made for), so
    // that a world tile's kept state and its residency see it.
    void writeActivity(VegetationTile& tile) const;

    std::vector<uint32_t> activeFields() const; // ascending field indices
    uint64_t tick() const { return tick_; }     // the next tick step() simulates
    bool fieldActive(uint32_t field) const { return active_[field] != 0; }
    uint64_t lastContactTick(uint32_t field) const { return lastContact_[field]; }
    const InteractionParams& params() const { return params_; }
    uint32_t threads() const { return threads_; }
    void setThreads(uint32_t threads); // >= 1
    uint32_t plantCount() const { return plantCount_; }
    // Every plant's dynamic record as generated (the tile's record-buffer order): the state at tick 0.
    std::vector<gpu::PlantDynamic> initialDynamics() const;

    // Writes tick, field activity, the given dynamic records (the GPU's, read back; plantCount() of them) and the
    // ground's ruts atomically to path. Throws sward::Error naming the file.
    void saveState(const std::string& path, std::span<const gpu::PlantDynamic> dynamics,
                   const TrackBlocks& tracks) const;
    // Loads a state written by saveState for this tile, restores tick and field activity and returns the state:
    // its dynamic records to upload and its ruts. Throws sward::Error naming the file if it is invalid or belongs to
    // another tile; the world is unchanged then.
    InteractionState restoreState(const std::string& path);

private:
    const VegetationTile* tile_;
    InteractionParams params_;
    CollisionPass pass_;
    uint32_t threads_;
    uint32_t plantCount_ = 0;
    uint64_t tick_ = 0;
    std::vector<uint8_t> active_;
    std::vector<uint64_t> lastContact_;
};

// What the GPU does with one tick, on the CPU: applies result's contacts (applyContact) to dynamics (indexed by
// tile plant index), then advances every plant of every field in activeFields by one recoverStep.
void simulateOnCpu(std::vector<gpu::PlantDynamic>& dynamics, const TickResult& result,
                   const std::vector<uint32_t>& activeFields, const VegetationTile& tile, const RecoveryParams& params);

} // namespace sward
