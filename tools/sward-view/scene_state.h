// SceneState: everything the viewer builds from a scene file (terrain, tile, objects, renderer, simulation,
// overlay). Rebuilt on reload, density or MSAA changes.
#pragma once

#include "engine/context.h"
#include "overlay.h"
#include "render/object_renderer.h"
#include "render/scene_renderer.h"
#include "render/simulation.h"
#include "scene/scene.h"

#include <memory>
#include <optional>
#include <vector>

namespace sward {

// Members are declared in construction order, so the simulation (which uses the renderer's buffers) is
// destroyed first.
struct SceneState {
    Scene scene;
    Heightfield terrain;
    std::optional<VegetationTile> tile;
    std::vector<ObjectModel> models; // the scene's glTF objects (drawn and colliding)
    std::optional<size_t> roverObject; // the keyboard rover's glTF model: the object after the scene's own
    std::unique_ptr<SceneRenderer> renderer;
    std::unique_ptr<Simulation> simulation;
    std::unique_ptr<Overlay> overlay;
};

// Builds the scene's state for `samples` (1 or 4) MSAA samples, with the default rover model (when installed)
// added as one more, hidden, scene object.
std::unique_ptr<SceneState> loadSceneState(Context& ctx, const Scene& sceneIn, uint32_t samples);

} // namespace sward
