#include "render/scene_gpu.h"

#include "common/error.h"
#include "render/vegetation_renderer.h"

namespace sward {

SceneGpu createSceneGpu(Context& ctx, SceneResources& resources, uint32_t samples, SimulationMode mode) {
    require(samples == 1 || samples == 4, "MSAA samples must be 1 or 4 (got " + std::to_string(samples) + ")");
    SceneGpu gpu;
    if (resources.world) {
        // The budget is the scene's (never derived from the machine: what a scene renders must not depend on it), so
        // a budget the GPU cannot hold is refused here, as parseWorldParams refuses one over the machine's memory.
        const uint64_t budget = resources.scene.world.memoryBudgetBytes, local = ctx.device.deviceLocalBytes();
        require(budget <= local, resources.scene.source + ": 'world.memory_budget_mib' (" +
                                     std::to_string(budget >> 20) + " MiB) is more than the GPU '" +
                                     ctx.device.name() + "' has (" + std::to_string(local >> 20) +
                                     " MiB of device-local memory)");
        gpu.renderer = std::make_unique<SceneRenderer>(ctx, resources.scene,
                                                       samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                                                       resources.atlas ? &*resources.atlas : nullptr,
                                                       &resources.models);
        resources.atlas.reset();
        if (mode != SimulationMode::None && (resources.vegetation || sceneMakesRuts(resources.scene)) &&
            sceneHasColliders(resources.scene))
            gpu.worldSimulation = std::make_unique<WorldSimulation>(ctx, resources, *gpu.renderer);
        return gpu;
    }
    VegetationTile* tile = resources.tile ? &*resources.tile : nullptr;
    gpu.renderer = std::make_unique<SceneRenderer>(ctx, resources.scene, resources.terrain,
                                                   samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT, tile,
                                                   resources.atlas ? &*resources.atlas : nullptr, &resources.models,
                                                   resources.cover ? &*resources.cover : nullptr);
    resources.atlas.reset(); // uploaded: nothing reads the CPU copies again
    resources.cover.reset();
    const bool simulate = mode == SimulationMode::Always ||
                          (mode == SimulationMode::WhenSceneHasColliders && sceneHasColliders(resources.scene));
    const bool plants = tile && gpu.renderer->vegetation();
    // Without plants the colliders still press ruts into the ground, if any asks for them.
    if (simulate && (plants || sceneMakesRuts(resources.scene))) {
        gpu.simulation = std::make_unique<Simulation>(ctx, resources.scene, resources.terrain, plants ? tile : nullptr,
                                                      plants ? &gpu.renderer->vegetation()->buffers() : nullptr);
        gpu.simulation->setObjectModels(&resources.models);
        gpu.renderer->setGroundTracks(&gpu.simulation->tracks(), &resources.terrain);
    }
    // Uploaded; only the collision pass and the range sensors (range/range_recorder.h) read the CPU copy.
    if ((!plants || !gpu.simulation) && resources.scene.rangeSensors.empty()) resources.tile.reset();
    return gpu;
}

uint32_t syncWorldTiles(SceneRenderer& renderer, const WorldTiles& world) {
    std::vector<TileCoord> resident = world.residentTiles(), gone;
    for (TileCoord coord : renderer.tiles())
        if (!world.find(coord)) gone.push_back(coord);
    for (TileCoord coord : gone) renderer.removeTile(coord);
    uint32_t added = 0;
    for (TileCoord coord : resident) {
        if (renderer.hasTile(coord)) continue;
        const WorldTile& tile = *world.find(coord);
        renderer.addTile(coord, tile.ground, &tile.vegetation, tile.cover.texels.empty() ? nullptr : &tile.cover);
        ++added;
    }
    return added;
}

} // namespace sward
