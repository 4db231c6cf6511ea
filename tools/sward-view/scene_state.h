// SceneState: everything the viewer builds from a scene file: the shared CPU assembly (SceneResources), its GPU
// side (SceneGpu, always with a simulation: the user's rover may touch plants at any time) and the overlay.
// Rebuilt on reload, density or MSAA changes.
#pragma once

#include "engine/context.h"
#include "overlay.h"
#include "render/object_renderer.h"
#include "render/scene_gpu.h"
#include "scene/scene_resources.h"

#include <memory>
#include <optional>

namespace sward {

// Members are declared in construction order: the GPU side (which reads the resources) is destroyed first.
struct SceneState {
    SceneResources resources;
    std::optional<size_t> roverObject; // the keyboard rover's glTF model: the object after the scene's own
    SceneGpu gpu;
    std::unique_ptr<Overlay> overlay;
};

// Builds the scene's state for `samples` (1 or 4) MSAA samples, with the default rover model (when installed)
// added as one more, hidden, scene object.
std::unique_ptr<SceneState> loadSceneState(Context& ctx, const Scene& sceneIn, uint32_t samples);

} // namespace sward
