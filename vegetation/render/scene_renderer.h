// SceneRenderer: draws a scene (terrain, sky; vegetation once loaded) into a RenderTarget.
//
// Attachment contract of the main pass (see docs/architecture.md):
//   0  RGBA16F  linear HDR radiance (averaged over MSAA samples by the resolve)
//   1  R32_UINT bit pattern of the planar depth in metres (+inf for sky), resolved with SAMPLE_ZERO
#pragma once

#include "camera.h"
#include "context.h"
#include "heightfield.h"
#include "pipelines.h"
#include "render_target.h"
#include "scene.h"

#include <array>
#include <memory>

namespace sward {

class GpuTimers;

// Formats and clear values of the main pass, in attachment order.
RenderTargetDesc mainPassTargetDesc(uint32_t width, uint32_t height, uint32_t samples);

class SceneRenderer {
public:
    SceneRenderer(Context& ctx, const Scene& scene, const Heightfield& terrain, VkSampleCountFlagBits samples);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // Records the whole frame into `cmd`: constants, terrain, sky. `frameIndex` selects the constants slot,
    // so up to kFramesInFlight frames may be in flight. Timers (optional) get one entry per pass.
    void record(VkCommandBuffer cmd, RenderTarget& target, const Camera& camera, double timeSeconds,
                uint32_t frameIndex, GpuTimers* timers = nullptr);

    static constexpr uint32_t kFramesInFlight = 3;

private:
    void writeConstants(uint32_t slot, const Camera& camera, double timeSeconds);

    Context& ctx_;
    Scene scene_;
    Buffer terrainVertices_, terrainIndices_;
    uint32_t terrainIndexCount_ = 0;
    Buffer constants_; // kFramesInFlight slots of FrameConstants, host-visible
    uint64_t constantsStride_ = 0;
    Pipeline terrainPipeline_, skyPipeline_;
};

// Host copy of one rendered frame.
struct FrameImages {
    uint32_t width = 0, height = 0;
    std::vector<uint16_t> rgbaHalf; // width*height*4 half floats, top row first
    std::vector<float> depth;       // planar metres, +inf where nothing was hit
};

// Renders one frame into a fresh target and reads colour and depth back (waits for the GPU).
FrameImages renderFrame(Context& ctx, SceneRenderer& renderer, const Camera& camera, uint32_t samples,
                        double timeSeconds = 0.0);

} // namespace sward
