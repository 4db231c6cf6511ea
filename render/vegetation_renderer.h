// VegetationRenderer: per-frame compute expansion of point plants into LOD instances and their draws.
//
// Frame flow (docs/architecture.md):
//   expand()  count pass (workgroup per cluster: frustum + distance cull, LOD choice, per-LOD counts)
//             -> scan (one workgroup: exclusive prefix sums in cluster order -> offsets + 3 indirect draws)
//             -> write pass (same choices; instances written at offset + rank: a fixed, deterministic order)
//   draw()    three vkCmdDrawIndirect (near 4 quads, mid 2 quads, far 1 billboard) into the current pass:
//             main colour (alpha-to-coverage at 4x MSAA, alpha test at 1x), ground truth or sun shadow map.
#pragma once

#include "vegetation/atlas.h"
#include "world/camera.h"
#include "engine/context.h"
#include "engine/pipelines.h"
#include "scene/scene.h"
#include "render/vegetation_buffers.h"

#include "shared/config.h"
#include "shared/gpu_layout.h"

namespace sward {

enum class PlantPass { Main, Truth, Shadow };

// The latest expansion baked into static vertices ([near | mid | far]), for baselines and reference tests.
struct BakedPlants {
    Buffer vertices;          // gpu::BakedVertex[vertexCount]
    uint32_t vertexCount = 0;
    gpu::ExpansionStats stats{};
};

struct VegetationPassFormats {
    VkFormat mainColor, mainDepth;
    VkSampleCountFlagBits mainSamples;
    VkFormat truthDepthBits, truthLabel, truthDepth; // truth colour attachments: depth bits, label
    VkFormat shadowDepth;
};

class VegetationRenderer {
public:
    // Uploads the tile and the atlas (with its mip chain) and builds the pipelines.
    VegetationRenderer(Context& ctx, const Scene& scene, const VegetationTile& tile, const Atlas& atlas,
                       const VegetationPassFormats& formats);
    ~VegetationRenderer();
    VegetationRenderer(const VegetationRenderer&) = delete;
    VegetationRenderer& operator=(const VegetationRenderer&) = delete;

    // Records the three expansion dispatches for this camera and simulation time. `slot` selects the
    // constants slot (taken modulo gpu::kFrameDataSlots).
    // `cullPlanes` (optional) replaces the camera's frustum for culling, e.g. the union of a stereo pair's.
    void expand(VkCommandBuffer cmd, const Camera& camera, double timeSeconds, uint32_t slot,
                const std::array<glm::vec4, 5>* cullPlanes = nullptr);
    // Records the plant draws into the current rendering pass. `frame` is the frame-constants binding;
    // `shadowMap` is the sampled sun shadow map for the main pass (ignored otherwise).
    void draw(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame, const DescriptorBinding& shadowMap,
              uint32_t slot);

    // Statistics of the latest expansion (reads back; waits for the GPU).
    gpu::ExpansionStats readStats();
    // Bakes the latest expansion's quads into static vertices (one submission; waits).
    BakedPlants bake(uint32_t slot);
    // Draws baked vertices into the current main pass, with the main pass's fragment shading.
    void drawBaked(VkCommandBuffer cmd, const BakedPlants& baked, const DescriptorBinding& frame,
                   const DescriptorBinding& shadowMap, uint32_t slot);
    void destroyBaked(BakedPlants& baked);
    // Live changes from the viewer's panel; used by the next expand().
    void setWindAndLod(const WindParams& wind, const LodParams& lod) {
        scene_.wind = wind;
        scene_.lod = lod;
    }
    VegetationBuffers& buffers() { return buffers_; }
    uint32_t instanceCapacity() const { return capacity_; }
    // Instances and their draw commands, for benchmarks that re-draw a frozen expansion.
    const Buffer& instances() const { return instances_; }
    const Buffer& drawCommands() const { return draws_; }

private:
    void uploadAtlas(const Atlas& atlas);
    DescriptorBinding constantsBinding(uint32_t slot) const;
    DescriptorBinding atlasCellsBinding() const;
    DescriptorBinding atlasBinding() const;

    Context& ctx_;
    Scene scene_;
    VegetationBuffers buffers_;
    uint32_t capacity_ = 0;
    uint32_t atlasMaxColumns_ = 1;
    glm::uvec4 atlasColumns_{1u};
    Buffer constants_, clusterCounts_, instances_, instancePlants_, draws_, stats_, atlasCells_;
    uint64_t constantsStride_ = 0;
    Image atlasImage_;
    VkSampler atlasSampler_ = VK_NULL_HANDLE;
    Pipeline countPipeline_, scanPipeline_, writePipeline_;
    Pipeline mainPipeline_, truthPipeline_, shadowPipeline_;
    Pipeline bakePipeline_, staticPipeline_; // created on first use (benchmarks, tests)
    VegetationPassFormats formats_;
};

} // namespace sward
