#include "scene_state.h"


#include <cstdio>
#include <filesystem>
#include <string>

#ifndef SWARD_SOURCE_DIR
#define SWARD_SOURCE_DIR "."
#endif

namespace sward {

namespace {

// The default rover model (sward-rover), drawn where the keyboard rover drives; none if it is not installed.
std::string roverModelPath() {
    for (std::string path : {std::string("examples/assets/rover.gltf"), std::string(SWARD_SOURCE_DIR) + "/examples/assets/rover.gltf"})
        if (std::filesystem::exists(path)) return path;
    return {};
}

} // namespace

std::unique_ptr<SceneState> loadSceneState(Context& ctx, const Scene& sceneIn, uint32_t samples) {
    // The keyboard rover is drawn as one more scene object without colliders (its wheels collide through
    // Simulation::setExternalColliders); ObjectRenderer::place moves it every frame.
    Scene scene = sceneIn;
    std::optional<size_t> roverObject;
    const bool world = scene.world.enabled && scene.world.tilesX * scene.world.tilesY > 1; // no objects (yet)
    if (std::string model = roverModelPath(); !model.empty() && !world) {
        ObjectParams rover;
        rover.name = "sward-view rover";
        rover.model = model;
        rover.path.points = {glm::dvec2(0.0)};
        roverObject = scene.objects.size();
        scene.objects.push_back(rover);
    }
    auto state = std::make_unique<SceneState>(SceneState{.resources = buildSceneResources(std::move(scene)),
                                                         .roverObject = roverObject});
    state->gpu = createSceneGpu(ctx, state->resources, samples, SimulationMode::Always);
    // A world always simulates (the keyboard rover may press plants and ruts at any time), on the tiles resident as
    // they are: the viewer never waits for a tile's generation (tools/sward-view/world_drive.h).
    if (state->resources.world && !state->gpu.worldSimulation &&
        (state->gpu.renderer->vegetation() || sceneMakesRuts(state->resources.scene)))
        state->gpu.worldSimulation = std::make_unique<WorldSimulation>(ctx, state->resources, *state->gpu.renderer);
    if (state->gpu.worldSimulation) state->gpu.worldSimulation->setWaitForTiles(false);
    if (state->roverObject && state->gpu.renderer->objects())
        state->gpu.renderer->objects()->setVisible(*state->roverObject, false);
    state->overlay = std::make_unique<Overlay>(ctx, samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT);
    return state;
}

} // namespace sward
