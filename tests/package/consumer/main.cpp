// The smallest program built against an installed sward: load a scene, build its resources, create the device and
// the renderer, render one frame headless and report what it saw. Exit 0 when ground and sky are both in view and validation
// (when on) reported nothing.
#include "common/error.h"
#include "engine/context.h"
#include "render/scene_gpu.h"
#include "scene/scene_resources.h"

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: consumer SCENE.json\n");
        return 2;
    }
    try {
        sward::Scene scene = sward::loadScene(argv[1]);
        sward::SceneResources resources = sward::buildSceneResources(std::move(scene));
        sward::Context ctx(sward::DeviceOptions{.quiet = true});
        sward::SceneGpu gpu = sward::createSceneGpu(ctx, resources, 1, sward::SimulationMode::None);
        const sward::Camera camera = sward::sceneCamera(resources.scene, resources.terrain, 96, 64);
        const sward::FrameImages frame = sward::renderFrame(ctx, *gpu.renderer, camera);
        size_t ground = 0;
        for (float z : frame.depth) ground += std::isfinite(z) ? 1 : 0;
        std::printf("consumer: %ux%u frame, %zu of %zu pixels hit the ground or plants\n", frame.width, frame.height,
                    ground, frame.depth.size());
        if (ctx.device.validationMessageCount() > 0) return 1; // SWARD_VALIDATION=1 in the tests
        return ground > 0 && ground < frame.depth.size() ? 0 : 1;
    } catch (const sward::Error& e) {
        std::fprintf(stderr, "consumer: error: %s\n", e.what());
        return 1;
    }
}
