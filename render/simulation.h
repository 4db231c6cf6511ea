// Simulation: the fixed-tick interaction loop of a sequence. Tick t happens at time t * timeStep: the scene's
// actors give the colliders, the CPU collision pass (InteractionWorld) gives contacts and active fields, and
// the GPU applies them and runs the recovery pass (InteractionGpu). Frame f shows the state after tick f.
// Ticks are never skipped: rendering frames A..B first simulates ticks 0..A-1, so a shard or a resumed run
// shows exactly what a full run shows.
#pragma once

#include "interaction/interaction.h"
#include "render/interaction_gpu.h"
#include "scene/scene.h"

#include <memory>

namespace sward {

class Simulation {
public:
    // `tile` must outlive the simulation (the collision pass reads its static records).
    Simulation(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationTile& tile,
               VegetationBuffers& buffers, uint32_t threads = 0);

    uint64_t nextTick() const { return world_.tick(); }
    // Simulates every tick before `tick` that has not run yet, each in its own submission (waits).
    void runTicksBefore(uint64_t tick);
    // Runs the collision pass of the next tick and records its GPU update into `cmd`.
    void recordNextTick(VkCommandBuffer cmd, uint32_t slot);
    // The scene objects' models (loadObjectModels), for their node colliders; must outlive the simulation.
    void setObjectModels(const std::vector<ObjectModel>* models) { models_ = models; }
    // Colliders not described by the scene (e.g. a vehicle driven live in sward-view), added to the scene
    // actors' colliders of every following tick until replaced. Ids must not clash with actorColliders' ids.
    void setExternalColliders(std::vector<Collider> colliders) { external_ = std::move(colliders); }
    const std::vector<Collider>& lastColliders() const { return lastColliders_; } // of the latest tick

    InteractionWorld& world() { return world_; }
    InteractionGpu& gpu() { return gpu_; }
    const TickResult& lastTick() const { return last_; }
    double collisionMs() const { return collisionMs_; } // CPU collision time summed over all ticks

private:
    Context& ctx_;
    const Scene& scene_;
    const Ground& terrain_;
    InteractionWorld world_;
    InteractionGpu gpu_;
    TickResult last_;
    std::vector<Collider> external_, lastColliders_;
    const std::vector<ObjectModel>* models_ = nullptr;
    double collisionMs_ = 0.0;
};

} // namespace sward
