#include "render/simulation.h"

#include "common/parallel_for.h"

#include <thread>

namespace sward {

Simulation::Simulation(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationTile& tile,
                       VegetationBuffers& buffers, uint32_t threads)
    : ctx_(ctx), scene_(scene), terrain_(terrain),
      world_(tile, scene.vegetation, scene.interaction, resolveThreadCount(threads)),
      gpu_(ctx, buffers) {}

void Simulation::recordNextTick(VkCommandBuffer cmd, uint32_t slot) {
    uint64_t tick = world_.tick();
    static const std::vector<ObjectModel> kNoModels;
    std::vector<Collider> colliders = sceneColliders(scene_, models_ ? *models_ : kNoModels, terrain_, tick);
    colliders.insert(colliders.end(), external_.begin(), external_.end());
    last_ = world_.step(colliders);
    lastColliders_ = std::move(colliders);
    collisionMs_ += last_.stats.cpuMs;
    gpu_.record(cmd, last_.contacts, last_.activeFields, scene_.interaction.recovery, slot);
}

void Simulation::runTicksBefore(uint64_t tick) {
    while (world_.tick() < tick) {
        uint32_t slot = uint32_t(world_.tick());
        ctx_.submitter.immediate([&](VkCommandBuffer cmd) { recordNextTick(cmd, slot); });
    }
}

} // namespace sward
