#include "simulation.h"

#include <thread>

namespace sward {

Simulation::Simulation(Context& ctx, const Scene& scene, const Heightfield& terrain, const VegetationTile& tile,
                       VegetationBuffers& buffers, uint32_t threads)
    : ctx_(ctx), scene_(scene), terrain_(terrain),
      world_(tile, scene.vegetation, scene.interaction, threads ? threads : std::max(1u, std::thread::hardware_concurrency())),
      gpu_(ctx, buffers) {}

void Simulation::recordNextTick(VkCommandBuffer cmd, uint32_t slot) {
    uint64_t tick = world_.tick();
    double time = double(tick) * scene_.sequence.timeStep;
    std::vector<Collider> colliders =
        actorColliders(scene_.actors, terrain_, time, tick, float(scene_.sequence.timeStep));
    last_ = world_.step(colliders);
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
