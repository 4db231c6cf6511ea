#include "render_job.h"

#include "atlas.h"
#include "context.h"
#include "image_files.h"
#include "scene.h"
#include "scene_renderer.h"

#include <chrono>
#include <cmath>
#include <cstdio>

namespace sward {

void runRenderJob(const RenderJobOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();

    // Everything that can be checked without a GPU is checked first, so bad input fails fast and cleanly.
    Scene scene = options.scenePath.empty() ? parseScene(nlohmann::json::object(), "<built-in>")
                                            : loadScene(options.scenePath);
    uint32_t width = scene.render.width, height = scene.render.height;
    if (options.resolution) parseResolution(*options.resolution, width, height);
    uint32_t samples = options.samples.value_or(scene.render.samples);
    require(std::isfinite(options.time) && options.time >= 0.0, "--time must be a finite, non-negative number of seconds");
    require(samples == 1 || samples == 4, "--samples must be 1 or 4 (got " + std::to_string(samples) + ")");
    if (options.cameraPosition) {
        scene.camera.position = *options.cameraPosition;
        scene.camera.useHeightAboveGround = false;
    }
    if (options.cameraLookAt) {
        scene.camera.lookAt = *options.cameraLookAt;
        scene.camera.lookAtUsesGround = false;
    }
    if (options.fovYDegrees) {
        require(*options.fovYDegrees >= 1.0 && *options.fovYDegrees <= 170.0, "--fov must be between 1 and 170 degrees");
        scene.camera.fovYDegrees = *options.fovYDegrees;
    }
    for (const char* sub : {"", "/left", "/depth", "/preview"}) ensureWritableDirectory(options.outDir + sub);

    Heightfield terrain = buildTerrain(scene);
    Camera camera = sceneCamera(scene, terrain, width, height);
    // All CPU-side loading (and its errors) happens before the GPU is touched: a scene that fails to load
    // allocates nothing on the device.
    std::optional<VegetationTile> vegetation;
    std::optional<Atlas> atlas;
    if (scene.vegetationEnabled && !options.noVegetation) {
        vegetation = buildVegetation(scene, terrain);
        atlas = buildAtlas(scene);
    }

    Context ctx(DeviceOptions{.deviceFilter = options.device, .validation = options.validation || DeviceOptions{}.validation});
    FrameImages frame;
    {
        SceneRenderer renderer(ctx, scene, terrain, samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                               vegetation ? &*vegetation : nullptr, atlas ? &*atlas : nullptr);
        vegetation.reset(); // uploaded: the CPU copy is no longer needed
        frame = renderFrame(ctx, renderer, camera, options.time);
    }
    const std::string name = "000000";
    writeExrRgbaHalf(options.outDir + "/left/" + name + ".exr", width, height, frame.rgbaHalf);
    writeExrDepth(options.outDir + "/depth/" + name + ".exr", width, height, frame.depth);
    writePng8(options.outDir + "/preview/" + name + ".png", width, height, 3,
              tonemapPreview(frame.rgbaHalf, width, height));

    uint32_t messages = ctx.device.validationMessageCount();
    require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("sward-render: %s, %ux%u, %ux MSAA -> %s (left/, depth/, preview/) in %.2f s\n", scene.name.c_str(),
                width, height, samples, options.outDir.c_str(), seconds);
}

} // namespace sward
