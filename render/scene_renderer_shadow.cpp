// SceneRenderer's sun shadow pass (render/scene_renderer.h): the cascades' image, their fit to the reference
// camera, and the pass that draws the terrain, objects and the plants' LODs that can reach each cascade.
#include "render/scene_renderer.h"

#include "engine/timestamps.h"
#include "render/object_renderer.h"
#include "render/vegetation_renderer.h"
#include "shared/config.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace sward {

void SceneRenderer::fitShadowImage(bool vegetation) {
    // The vegetation's LODs place the cascades. Checked before any Vulkan object is made, so a scene the device
    // cannot render is one error that leaves nothing behind.
    shadowParams_ = makeShadowCascadeParams(vegetation);
    const uint32_t width = shadowMapExtent(shadowParams_).x;
    const uint32_t largest = ctx_.device.properties().limits.maxImageDimension2D;
    require(width <= largest, scene_.source + ": 'render.shadow_map_size' " +
                                  std::to_string(scene_.render.shadowMapSize) + " with " +
                                  std::to_string(scene_.render.shadowCascades) + " 'render.shadow_cascades' needs a " +
                                  std::to_string(width) + " texel wide shadow image; this device's largest is " +
                                  std::to_string(largest));
}

void SceneRenderer::createShadowMap() {
    // Sun shadow map: the cascades' square maps in a row, always present (1x1 and disabled when shadow_map_size is
    // 0) so bindings stay valid.
    const glm::uvec2 shadowExtent = shadowMapExtent(shadowParams_);
    shadowMap_ = std::make_unique<RenderTarget>(ctx_, RenderTargetDesc{.width = shadowExtent.x,
                                                                       .height = shadowExtent.y,
                                                                       .depthFormat = VK_FORMAT_D32_SFLOAT,
                                                                       .depthClear = 0.0f,
                                                                       .sampleDepth = true});
}

ShadowCascadeParams SceneRenderer::makeShadowCascadeParams(bool vegetation) const {
    return ShadowCascadeParams{.cascades = scene_.render.shadowCascades,
                               .firstDistance = scene_.render.shadowDistance,
                               .lastDistance = double(scene_.lod.farLimit) + double(scene_.lod.band),
                               .farPlantsFrom =
                                   vegetation ? double(scene_.lod.midToFar) - 0.5 * double(scene_.lod.band) : 0.0,
                               .mapSize = std::max(scene_.render.shadowMapSize, 1u),
                               .casterMargin = shadowCasterReach(scene_.sun.direction().z),
                               .heightRange = double(terrainMaxHeight_ - terrainMinHeight_),
                               .blend = double(gpu::kShadowBlend)};
}

SceneRenderer::ShadowFit SceneRenderer::fitShadows(const Camera& reference) const {
    return {fitShadowCascades(reference, glm::dvec3(scene_.sun.direction()), shadowParams_), reference.position};
}

namespace {

// Plant LODs whose distance range (with their cross-fade bands) comes within `margin` of [begin, end]: the plants
// that can shade a receiver of that shell. Bit l: LOD l.
uint32_t lodsReaching(const LodParams& lod, double begin, double end, double margin) {
    const double half = 0.5 * lod.band;
    const double from[gpu::kLodCount] = {0.0, lod.nearToMid - half, lod.midToFar - half};
    const double to[gpu::kLodCount] = {lod.nearToMid + half, lod.midToFar + half, lod.farLimit + half};
    uint32_t mask = 0;
    for (uint32_t l = 0; l < gpu::kLodCount; ++l)
        if (from[l] <= end + margin && to[l] >= begin - margin) mask |= 1u << l;
    return mask;
}

} // namespace

void SceneRenderer::recordShadowPass(VkCommandBuffer cmd, const Camera& reference, const ShadowFit& shadow,
                                     uint32_t firstSlot, uint32_t dataSlot, double timeSeconds, GpuTimers* timers) {
    if (timers) timers->begin(cmd, "shadow");
    shadowMap_->begin(cmd);
    if (scene_.render.shadowMapSize > 0) {
        const std::vector<ShadowCascade>& cascades = shadow.cascades;
        for (uint32_t k = 0; k < cascades.size(); ++k) {
            const uint32_t slot = firstSlot + kMaxViews + k;
            writeConstants(slot, reference, shadow, timeSeconds, int(k));
            const uint32_t size = cascades[k].mapSize, offset = cascades[k].mapOffset;
            const VkViewport viewport{float(offset), 0.0f, float(size), float(size), 0.0f, 1.0f};
            const VkRect2D scissor{{int32_t(offset), 0}, {size, size}};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            const DescriptorBinding frame = frameBinding(slot);
            drawTerrain(cmd, PlantPass::Shadow, frame, reference.position);
            if (objects_) objects_->recordShadow(cmd, frame, dataSlot);
            if (vegetation_)
                vegetation_->draw(
                    cmd, PlantPass::Shadow, frame, shadowBinding(), dataSlot,
                    lodsReaching(scene_.lod, cascades[k].firstReceiver, cascades[k].end, shadowParams_.casterMargin));
        }
    }
    shadowMap_->end(cmd);
    if (timers) timers->end(cmd);
}

} // namespace sward
