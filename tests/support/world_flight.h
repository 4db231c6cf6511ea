// A camera flight over a world scene for the world tests (tests/render/world_render_test.cpp, gis_world_test.cpp,
// world_land_cover_render_test.cpp): one frame a second along the scene's camera path, each frame making the tiles
// within load_radius of the left camera resident (waitFor), uploading them and rendering the stereo pair. The tests
// fly a scene twice, streamed (a small load radius) and wholly resident, and compare the frames bitwise.
#pragma once

#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "scene/camera_rig.h"
#include "scene/scene_resources.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sward::test {

struct WorldFlight {
    std::vector<FrameImages> frames;
    std::vector<Camera> cameras; // left
    uint32_t mostTilesDrawn = 0, evicted = 0;
};

inline WorldFlight flyWorld(Context& ctx, Scene scene, uint32_t width, uint32_t height, uint32_t frames) {
    SceneResources r = buildSceneResources(std::move(scene), true, 2);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::None);
    OffscreenFrame target(ctx, width, height, 1);
    WorldFlight flight;
    for (uint32_t frame = 0; frame < frames; ++frame) {
        const double time = 1.0 * frame;
        const RigCameras rig = sceneRig(r.scene, cameraGround(r.scene, time), r.models, width, height, time);
        const glm::dvec2 camera(rig.left.position);
        r.world->waitFor({&camera, 1});
        syncWorldTiles(*gpu.renderer, *r.world);
        flight.mostTilesDrawn = std::max(flight.mostTilesDrawn, gpu.renderer->tileCount());
        flight.frames.push_back(target.render(*gpu.renderer, rig.left, time, frame, {}, &rig.right));
        flight.cameras.push_back(rig.left);
    }
    flight.evicted = uint32_t(r.world->stats().evicted);
    return flight;
}

} // namespace sward::test
