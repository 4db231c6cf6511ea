#include "render/horizon_ring.h"

#include "render/scene_renderer.h"
#include "scene/land_cover_params.h"
#include "scene/world_horizon.h"
#include "shared/gpu_layout.h"
#include "vegetation/grass_map.h"

#include <algorithm>
#include <cmath>

namespace sward {

GroundDrawMesh horizonRingMesh(const Heightfield& heights, float floorHeight) {
    GroundDrawMesh mesh = groundDrawMesh(Ground(heights));
    // Any triangle holding a point at distance d from the camera has its vertices within its diagonal of it.
    const float rim = heights.spacing() * std::sqrt(2.0f) * 1.01f;
    for (gpu::TerrainVertex& v : mesh.vertices) {
        v.normal.w = rim;
        v.uvLayer.w = floorHeight;
    }
    return mesh;
}

CoverMap horizonCover(const Scene& scene, const Heightfield& heights, std::span<const CategoryLook> looks) {
    const float side = std::max(heights.extent().x, heights.extent().y);
    const uint32_t cells = std::max(heights.columns(), heights.rows()) - 1;
    const uint32_t resolution = std::clamp(cells, 1u, kMaxCoverMapEdge);
    // A world's land cover, point-sampled like the meadow (issue 51, part B), else the procedural meadow.
    const glm::dvec2 origin(heights.origin());
    const GrassMap map =
        !scene.landCover.file.empty()
            ? worldLandCoverPointMap(scene, origin, side, resolution)
            : makeMeadowGrassMap({.resolution = resolution, .tileSize = side, .seed = scene.seed, .origin = origin});
    VegetationParams params = scene.vegetation;
    params.worldOrigin = heights.origin();
    params.tileSize = side;
    return makeCoverMap(map, looks, params);
}

// SceneRenderer's part of the ring (render/scene_renderer.h): made, drawn and released here.

void SceneRenderer::addHorizonRing(const Atlas* atlas) {
    const Heightfield heights = horizonHeights(scene_);
    const GroundDrawMesh mesh = horizonRingMesh(heights, terrainMinHeight_);
    auto ring = std::make_unique<TerrainTile>();
    ring->vertices = createBufferWithData(ctx_, bytesOf(mesh.vertices),
                                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ring->indices = createBufferWithData(ctx_, bytesOf(mesh.indices),
                                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ring->indexCount = uint32_t(mesh.indices.size());
    ring->boundsMin = glm::dvec2(heights.origin());
    ring->boundsMax = glm::dvec2(heights.origin() + heights.extent());
    CoverMap cover;
    if (atlas && scene_.vegetationEnabled && scene_.grassMapPath.empty())
        cover = horizonCover(scene_, heights, categoryLooks(*atlas, scene_.vegetation));
    uploadCoverMap(*ring, &cover);
    horizon_ = std::move(ring);
}

void SceneRenderer::releaseHorizonRing() {
    if (!horizon_) return;
    retireBuffer(ctx_, horizon_->vertices);
    retireBuffer(ctx_, horizon_->indices);
    retireImage(ctx_, horizon_->cover);
    retireImage(ctx_, horizon_->groundWeights);
    horizon_.reset();
}

uint32_t SceneRenderer::horizonTriangles() const {
    return horizon_ ? horizon_->indexCount / 3 : 0;
}

// As drawTerrain draws a tile without ruts, with the ring's kind in material.w (its fragments inside the disc go).
void SceneRenderer::drawHorizonRing(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame) {
    const TerrainTile& ring = *horizon_;
    const Pipeline& pipeline = pass == PlantPass::Main    ? terrainPipeline_
                               : pass == PlantPass::Truth ? terrainTruthPipeline_
                                                          : terrainTruthFlowPipeline_;
    bindPipeline(cmd, pipeline);
    const DescriptorBinding cover = sampledImage(gpu::kBindingCoverMap, ring.cover.view, coverSampler_);
    gpu::TerrainTileConstants constants{.coverRect = ring.coverRect, .material = groundMaterialConstants(scene_)};
    constants.material.y &= uint32_t(ring.groundMaterials);
    constants.material.w = gpu::kGroundHorizonRing;
    if (pass == PlantPass::Main) {
        const DescriptorBinding textures =
            sampledImage(gpu::kBindingGroundTextures, groundTextures_.view, groundSampler_);
        const DescriptorBinding weights =
            sampledImage(gpu::kBindingGroundMaterials, ring.groundWeights.view, coverSampler_);
        pushDescriptors(ctx_.device, cmd, pipeline, {frame, shadowBinding(), cover, textures, weights});
        pushConstants(cmd, pipeline, constants);
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &ring.vertices.handle, &offset);
        vkCmdBindIndexBuffer(cmd, ring.indices.handle, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, ring.indexCount, 1, 0, 0, 0);
        return;
    }
    const DescriptorBinding vertices = storageBuffer(gpu::kBindingMeshVertices, ring.vertices.handle);
    const DescriptorBinding indices = storageBuffer(gpu::kBindingMeshIndices, ring.indices.handle);
    pushDescriptors(ctx_.device, cmd, pipeline, {frame, vertices, indices, cover});
    pushConstants(cmd, pipeline, constants);
    vkCmdDraw(cmd, ring.indexCount, 1, 0, 0); // non-indexed: terrain_truth.vert reads the triangle list
}

} // namespace sward
