#include "render/simulation.h"

#include "common/error.h"
#include "common/parallel_for.h"

#include <cassert>

namespace sward {

Simulation::Simulation(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationTile* tile,
                       VegetationBuffers* buffers, uint32_t threads)
    : ctx_(ctx), scene_(scene), terrain_(terrain) {
    assert((tile == nullptr) == (buffers == nullptr));
    if (!tile) return;
    world_ =
        std::make_unique<InteractionWorld>(*tile, scene.vegetation, scene.interaction, resolveThreadCount(threads));
    gpu_ = std::make_unique<InteractionGpu>(ctx, *buffers);
}

InteractionWorld& Simulation::world() {
    assert(world_);
    return *world_;
}

InteractionGpu& Simulation::gpu() {
    assert(gpu_);
    return *gpu_;
}

std::vector<Collider> Simulation::collidersOf(uint64_t tick) const {
    static const std::vector<ObjectModel> kNoModels;
    std::vector<Collider> colliders = sceneColliders(scene_, models_ ? *models_ : kNoModels, terrain_, tick);
    colliders.insert(colliders.end(), external_.begin(), external_.end());
    return colliders;
}

void Simulation::recordNextTick(VkCommandBuffer cmd, uint32_t slot) {
    std::vector<Collider> colliders = collidersOf(tick_);
    if (world_) {
        last_ = world_->step(colliders);
        collisionMs_ += last_.stats.cpuMs;
        gpu_->record(cmd, last_.contacts, last_.activeFields, scene_.interaction.recovery, slot);
    }
    // Ruts sweep each collider from its pose at the previous tick (computed again after a restore).
    std::vector<Collider> recomputed;
    if (tick_ > 0 && lastColliders_.empty()) recomputed = collidersOf(tick_ - 1);
    tracks_.press(lastColliders_.empty() ? recomputed : lastColliders_, colliders, terrain_);
    lastColliders_ = std::move(colliders);
    ++tick_;
}

void Simulation::runTicksBefore(uint64_t tick) {
    while (tick_ < tick) {
        uint32_t slot = uint32_t(tick_);
        ctx_.submitter.immediate([&](VkCommandBuffer cmd) { recordNextTick(cmd, slot); });
    }
}

void Simulation::saveState(const std::string& path) {
    if (world_) return world_->saveState(path, gpu_->readDynamics(), tracks_.blocks());
    saveInteractionState(path, InteractionState{.tick = tick_, .tracks = tracks_.blocks()});
}

void Simulation::restoreState(const std::string& path) {
    InteractionState state;
    if (world_) {
        state = world_->restoreState(path);
        gpu_->writeDynamics(state.dynamics);
    } else {
        state = loadInteractionState(path);
        require(state.fieldActive.empty() && state.dynamics.empty(),
                path + ": the interaction state belongs to a scene with plants (" +
                    std::to_string(state.fieldActive.size()) + " fields, " + std::to_string(state.dynamics.size()) +
                    " plants); this one has none");
    }
    tick_ = state.tick;
    tracks_.restore(std::move(state.tracks));
    lastColliders_.clear(); // recomputed for the next tick's sweep
}

} // namespace sward
