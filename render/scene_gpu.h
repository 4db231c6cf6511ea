// SceneGpu: the GPU side of a SceneResources — its renderer and, when plants can be touched, the interaction
// simulation. The one place that turns CPU resources into GPU objects, for sward-render, sward-view and sward-bench.
#pragma once

#include "render/scene_renderer.h"
#include "render/simulation.h"
#include "render/world_simulation.h"
#include "scene/scene_resources.h"

#include <memory>

namespace sward {

enum class SimulationMode {
    None,                  // drawing only (benchmarks)
    WhenSceneHasColliders, // datasets: plants move only if the scene has actors or object colliders
    Always,                // the viewer: the user's rover may touch plants at any time
};

// Members in construction order: the simulations (which use the renderer's buffers) are destroyed first.
struct SceneGpu {
    std::unique_ptr<SceneRenderer> renderer;
    std::unique_ptr<Simulation> simulation;           // one tile: null without vegetation or without a simulation
    std::unique_ptr<WorldSimulation> worldSimulation; // a world with vehicles or colliders (SimulationMode not None)
};

// Uploads `resources` (terrain, objects, vegetation, atlas) with `samples` (1 or 4) MSAA. `resources` must outlive
// the result (the simulation reads the tile, scene, terrain and models). The CPU copies of the atlas and (without a
// simulation) of the tile are released once uploaded.
// A world (resources.world) starts with no tile: syncWorldTiles draws what is resident. Its actors touch plants through
// a WorldSimulation (not in SimulationMode::None), which then also decides what is resident.
SceneGpu createSceneGpu(Context& ctx, SceneResources& resources, uint32_t samples, SimulationMode mode);

// Makes the renderer's tiles those resident in `world`: drops the evicted, uploads the new (waits for the uploads,
// never for a generation). Returns how many tiles were uploaded.
uint32_t syncWorldTiles(SceneRenderer& renderer, const WorldTiles& world);

} // namespace sward
