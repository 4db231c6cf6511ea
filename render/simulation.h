// Simulation: the fixed-tick interaction loop of a sequence. Tick t happens at time t * timeStep: the scene's
// actors give the colliders, the CPU collision pass (InteractionWorld) gives contacts and active fields, and
// the GPU applies them and runs the recovery pass (InteractionGpu); the colliders that ask for it press ruts into
// the ground (GroundTracks, drawn by the scene renderer). Frame f shows the state after tick f.
// Ticks are never skipped: rendering frames A..B first simulates ticks 0..A-1, so a shard or a resumed run
// shows exactly what a full run shows.
#pragma once

#include "interaction/ground_tracks.h"
#include "interaction/interaction.h"
#include "render/interaction_gpu.h"
#include "scene/scene.h"

#include <memory>

namespace sward {

class Simulation {
public:
    // `tile` must outlive the simulation (the collision pass reads its static records); `tile` and `buffers` null:
    // a scene without plants, whose colliders only press ruts into the ground.
    Simulation(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationTile* tile,
               VegetationBuffers* buffers, uint32_t threads = 0);

    uint64_t nextTick() const { return tick_; }
    // Simulates every tick before `tick` that has not run yet, each in its own submission (waits).
    void runTicksBefore(uint64_t tick);
    // Runs the collision pass of the next tick, presses its ruts and records its GPU update into `cmd`.
    void recordNextTick(VkCommandBuffer cmd, uint32_t slot);
    // The scene objects' models (loadObjectModels), for their node colliders; must outlive the simulation.
    void setObjectModels(const std::vector<ObjectModel>* models) { models_ = models; }
    // Colliders not described by the scene (e.g. a vehicle driven live in sward-view), added to the scene
    // actors' colliders of every following tick until replaced. Ids must not clash with actorColliders' ids.
    void setExternalColliders(std::vector<Collider> colliders) { external_ = std::move(colliders); }
    const std::vector<Collider>& lastColliders() const { return lastColliders_; } // of the latest tick

    bool hasPlants() const { return world_ != nullptr; }
    InteractionWorld& world(); // requires hasPlants()
    InteractionGpu& gpu();     // requires hasPlants()
    const GroundTracks& tracks() const { return tracks_; }
    const TickResult& lastTick() const { return last_; }
    double collisionMs() const { return collisionMs_; } // CPU collision time summed over all ticks

    // Writes the state after the latest tick (tick, field activity, the GPU's dynamic records, ruts) atomically.
    void saveState(const std::string& path);
    // Continues from a state saveState wrote for this scene; errors name the file and leave the simulation as it was.
    void restoreState(const std::string& path);

private:
    std::vector<Collider> collidersOf(uint64_t tick) const;

    Context& ctx_;
    const Scene& scene_;
    const Ground& terrain_;
    std::unique_ptr<InteractionWorld> world_;
    std::unique_ptr<InteractionGpu> gpu_;
    GroundTracks tracks_;
    uint64_t tick_ = 0;
    TickResult last_;
    std::vector<Collider> external_, lastColliders_;
    const std::vector<ObjectModel>* models_ = nullptr;
    double collisionMs_ = 0.0;
};

} // namespace sward
