#include "render_job.h"

#include "atlas.h"
#include "context.h"
#include "image_files.h"
#include "scene.h"
#include "scene_renderer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <unistd.h>

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

    uint32_t firstFrame = 0, endFrame = scene.sequence.frames;
    if (options.frames) parseFrameRange(*options.frames, firstFrame, endFrame);

    Heightfield terrain = buildTerrain(scene);
    // All CPU-side loading (and its errors) happens before the GPU is touched: a scene that fails to load
    // allocates nothing on the device.
    std::optional<VegetationTile> vegetation;
    std::optional<Atlas> atlas;
    if (scene.vegetationEnabled && !options.noVegetation) {
        vegetation = buildVegetation(scene, terrain);
        atlas = buildAtlas(scene);
    }

    Context ctx(DeviceOptions{.deviceFilter = options.device, .validation = options.validation || DeviceOptions{}.validation});
    {
        SceneRenderer renderer(ctx, scene, terrain, samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                               vegetation ? &*vegetation : nullptr, atlas ? &*atlas : nullptr);
        vegetation.reset(); // uploaded: the CPU copy is no longer needed
        OffscreenFrame target(ctx, width, height, samples);
        const bool terminal = isatty(fileno(stderr));
        auto frameStart = Clock::now();
        for (uint32_t frame = firstFrame; frame < endFrame; ++frame) {
            double time = options.time + double(frame) * scene.sequence.timeStep;
            Camera camera = sceneCamera(scene, terrain, width, height, time);
            FrameImages images = target.render(renderer, camera, time, frame);
            char name[16];
            std::snprintf(name, sizeof name, "%06u", frame);
            writeExrRgbaHalf(options.outDir + "/left/" + name + ".exr", width, height, images.rgbaHalf);
            writeExrDepth(options.outDir + "/depth/" + name + ".exr", width, height, images.depth);
            writePng8(options.outDir + "/preview/" + name + ".png", width, height, 3,
                      tonemapPreview(images.rgbaHalf, width, height));
            if (terminal) {
                uint32_t done = frame + 1 - firstFrame, total = endFrame - firstFrame;
                double elapsed = std::chrono::duration<double>(Clock::now() - frameStart).count();
                double fps = done / std::max(elapsed, 1e-9);
                std::fprintf(stderr, "\rsward-render: frame %u/%u  %.2f frames/s  ETA %.0f s   ", done, total, fps,
                             double(total - done) / fps);
                if (done == total) std::fprintf(stderr, "\n");
            }
        }
    }

    uint32_t messages = ctx.device.validationMessageCount();
    require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("sward-render: %s, %u frame(s) %u:%u, %ux%u, %ux MSAA -> %s (left/, depth/, preview/) in %.2f s\n",
                scene.name.c_str(), endFrame - firstFrame, firstFrame, endFrame, width, height, samples,
                options.outDir.c_str(), seconds);
}

void parseFrameRange(const std::string& text, uint32_t& first, uint32_t& end) {
    unsigned a = 0, b = 0;
    char colon = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &colon, &b, &extra) != 3 || colon != ':' || a >= b ||
        text.find_first_not_of("0123456789:") != std::string::npos)
        throw Error("bad frame range '" + text + "': expected A:B with A < B (frames A .. B-1), e.g. 0:60");
    first = a;
    end = b;
}

} // namespace sward
