#include "render/scene_renderer.h"

#include "common/half_float.h"
#include "engine/barriers.h"
#include "engine/timestamps.h"
#include "render/ground_mesh.h"
#include "render/object_renderer.h"
#include "render/sky_constants.h"
#include "render/track_renderer.h"
#include "render/vegetation_renderer.h"
#include "scene/world_ground.h"
#include "shared/config.h"
#include "shared/gpu_layout.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>
#include <tuple>

namespace sward {

RenderTargetDesc mainPassTargetDesc(uint32_t width, uint32_t height, uint32_t samples) {
    VkClearColorValue black{.float32 = {0.0f, 0.0f, 0.0f, 1.0f}};
    return RenderTargetDesc{
        .width = width,
        .height = height,
        .samples = samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
        .colors = {{VK_FORMAT_R16G16B16A16_SFLOAT, black}},
        .depthFormat = VK_FORMAT_D32_SFLOAT,
        .depthClear = 0.0f,
    };
}

RenderTargetDesc truthPassTargetDesc(uint32_t width, uint32_t height, bool flow) {
    VkClearColorValue infinity{.uint32 = {gpu::kDepthInfinityBits, 0, 0, 0}};
    VkClearColorValue sky{.uint32 = {gpu::kSemanticSky << gpu::kInstanceBits, 0, 0, 0}};
    VkClearColorValue noNormal{.float32 = {0.0f, 0.0f, 0.0f, 0.0f}};
    // Normals in 32-bit floats: the dataset stores float32, and half floats would round a unit normal by 1e-3.
    RenderTargetDesc desc{
        .width = width,
        .height = height,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .colors = {{VK_FORMAT_R32_UINT, infinity},             // depth bits
                   {VK_FORMAT_R32G32_UINT, sky},               // (label, tile)
                   {VK_FORMAT_R32G32B32A32_SFLOAT, noNormal}}, // camera-frame normal, w unused
        .depthFormat = VK_FORMAT_D32_SFLOAT,
        .depthClear = 0.0f,
    };
    if (flow) // flow to the next and to the previous tick: x, y pixels, z the depth there, w 1 (0: no surface)
        desc.colors.insert(desc.colors.end(), 2, {VK_FORMAT_R32G32B32A32_SFLOAT, noNormal});
    return desc;
}

SceneRenderer::SceneRenderer(Context& ctx, const Scene& scene, const Ground& terrain, VkSampleCountFlagBits samples,
                             const VegetationTile* vegetation, const Atlas* atlas,
                             const std::vector<ObjectModel>* models, const CoverMap* cover)
    : ctx_(ctx), scene_(scene), samples_(samples == VK_SAMPLE_COUNT_4_BIT ? 4 : 1), objectGround_(&terrain) {
    writeSkyConstants(scene_, frameTemplate_);
    terrainMinHeight_ = terrain.minHeight();
    terrainMaxHeight_ = terrain.maxHeight();
    fitShadowImage(vegetation && atlas);
    uploadGroundTextures(&terrain);
    createPipelines(vegetation ? atlas : nullptr,
                    vegetation ? VegetationRenderer::instanceCapacityFor(countVegetation(*vegetation).plants) : 0);
    if (!scene.objects.empty())
        objects_ = models ? std::make_unique<ObjectRenderer>(ctx, scene, terrain, plantPassFormats(), *models)
                          : std::make_unique<ObjectRenderer>(ctx, scene, terrain, plantPassFormats());
    addTile(vegetation ? vegetation->coord : TileCoord{}, terrain, vegetation, cover);
}

SceneRenderer::SceneRenderer(Context& ctx, const Scene& scene, VkSampleCountFlagBits samples, const Atlas* atlas,
                             const std::vector<ObjectModel>* models)
    : ctx_(ctx), scene_(scene), samples_(samples == VK_SAMPLE_COUNT_4_BIT ? 4 : 1) {
    require(scene.world.enabled && (scene.objects.empty() || models),
            "SceneRenderer: a world scene, with its objects' models");
    writeSkyConstants(scene_, frameTemplate_);
    viewDistance_ = scene.world.viewDistance;
    // Bounds of the world's heights (procedural: +-amplitude / 2; a DEM's under the tiles): the same shadow depth
    // range whichever tiles are resident.
    std::tie(terrainMinHeight_, terrainMaxHeight_) = worldHeightRange(scene);
    fitShadowImage(atlas != nullptr);
    uploadGroundTextures(nullptr);
    createPipelines(atlas, VegetationRenderer::instanceCapacityFor(UINT32_MAX));
    if (!scene.objects.empty()) objects_ = std::make_unique<ObjectRenderer>(ctx, scene_, plantPassFormats(), *models);
    if (scene.world.horizon && scene.terrain.source != TerrainParams::Source::Mesh) addHorizonRing(atlas);
}

VegetationPassFormats SceneRenderer::plantPassFormats() const {
    const RenderTargetDesc mainDesc = mainPassTargetDesc(1, 1, samples_);
    const RenderTargetDesc truthDesc = truthPassTargetDesc(1, 1);
    return VegetationPassFormats{.mainColor = mainDesc.colors[0].format,
                                 .mainDepth = mainDesc.depthFormat,
                                 .mainSamples = mainDesc.samples,
                                 .truthDepthBits = truthDesc.colors[0].format,
                                 .truthLabel = truthDesc.colors[1].format,
                                 .truthNormal = truthDesc.colors[2].format,
                                 .truthDepth = truthDesc.depthFormat,
                                 .truthFlow = truthPassTargetDesc(1, 1, true).colors[3].format,
                                 .shadowDepth = VK_FORMAT_D32_SFLOAT};
}

void SceneRenderer::createPipelines(const Atlas* atlas, uint32_t instanceCapacity) {
    Context& ctx = ctx_;
    const Scene& scene = scene_;
    uint64_t align = ctx.device.properties().limits.minUniformBufferOffsetAlignment;
    constantsStride_ = (sizeof(gpu::FrameConstants) + align - 1) / align * align;
    constants_ = createBuffer(ctx, constantsStride_ * gpu::kFrameDataSlots * kSlotsPerFrame,
                              VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryIntent::Upload);

    RenderTargetDesc mainDesc = mainPassTargetDesc(1, 1, samples_);
    RenderTargetDesc truthDesc = truthPassTargetDesc(1, 1);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    PipelineLayoutDesc layout{
        .bindings = {layoutBinding(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, stages)}};
    PipelineLayoutDesc shadedLayout = layout; // + the sun shadow map
    shadedLayout.bindings.push_back(
        layoutBinding(gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT));
    PipelineLayoutDesc terrainLayout = shadedLayout; // + the tile's far cover, ground textures and material weights
    for (uint32_t binding : {gpu::kBindingCoverMap, gpu::kBindingGroundTextures, gpu::kBindingGroundMaterials})
        terrainLayout.bindings.push_back(
            layoutBinding(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT));
    terrainLayout.pushConstantSize = sizeof(gpu::TerrainTileConstants);
    terrainLayout.pushConstantStages = VK_SHADER_STAGE_FRAGMENT_BIT;
    coverSampler_ = createLinearSampler(ctx, 1);

    VkSamplerCreateInfo shadowSampler{
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_LINEAR,
        .minFilter = VK_FILTER_LINEAR,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .compareEnable = VK_TRUE,
        .compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL, // reversed Z: lit when not behind the stored occluder
    };
    VK_CHECK(vkCreateSampler(ctx.vk(), &shadowSampler, nullptr, &shadowSampler_));
    GraphicsPipelineDesc terrainDesc{
        .vertexShader = "terrain.vert",
        .fragmentShader = "terrain.frag",
        .vertexBindings = {{0, sizeof(gpu::TerrainVertex), VK_VERTEX_INPUT_RATE_VERTEX}},
        .vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::TerrainVertex, positionHeight)},
                             {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::TerrainVertex, normal)},
                             {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::TerrainVertex, albedo)},
                             {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::TerrainVertex, uvLayer)}},
        .cullMode = VK_CULL_MODE_BACK_BIT,
        .colorFormats = {mainDesc.colors[0].format},
        .depthFormat = mainDesc.depthFormat,
        .samples = mainDesc.samples,
    };
    terrainPipeline_ = createGraphicsPipeline(ctx.device, terrainDesc, terrainLayout);
    // Same triangles and rasterisation, pulled from storage buffers so each vertex knows its triangle's normal
    // (terrain_truth.vert); ground-truth outputs, one sample per pixel.
    GraphicsPipelineDesc truthTerrain = terrainDesc;
    truthTerrain.vertexShader = "terrain_truth.vert";
    truthTerrain.fragmentShader = "truth.frag";
    truthTerrain.vertexBindings = {};
    truthTerrain.vertexAttributes = {};
    truthTerrain.colorFormats = {truthDesc.colors[0].format, truthDesc.colors[1].format, truthDesc.colors[2].format};
    truthTerrain.samples = truthDesc.samples;
    PipelineLayoutDesc truthLayout = layout; // + the pulled vertices and triangle list, the cover map (turf labels)
    for (uint32_t binding : {gpu::kBindingMeshVertices, gpu::kBindingMeshIndices})
        truthLayout.bindings.push_back(
            layoutBinding(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT));
    truthLayout.bindings.push_back(
        layoutBinding(gpu::kBindingCoverMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT));
    truthLayout.pushConstantSize = sizeof(gpu::TerrainTileConstants);
    truthLayout.pushConstantStages = VK_SHADER_STAGE_FRAGMENT_BIT;
    terrainTruthPipeline_ = createGraphicsPipeline(ctx.device, truthTerrain, truthLayout);
    const VkFormat flowFormat = scene.render.flow ? plantPassFormats().truthFlow : VK_FORMAT_UNDEFINED;
    if (scene.render.flow)
        terrainTruthFlowPipeline_ =
            createGraphicsPipeline(ctx.device, truthFlowPipelineDesc(truthTerrain, flowFormat), truthLayout);
    if (sceneMakesRuts(scene))
        tracks_ =
            std::make_unique<TrackRenderer>(ctx, terrainDesc, terrainLayout, truthTerrain, truthLayout, flowFormat);
    terrainDesc.fragmentShader = "";
    terrainDesc.colorFormats = {};
    terrainDesc.samples = VK_SAMPLE_COUNT_1_BIT;
    terrainDesc.cullMode = VK_CULL_MODE_NONE; // hills facing away from the sun still cast shadows
    terrainDesc.specialization = {/* PASS= */ gpu::kPassShadow};
    terrainDesc.depthBias = -1.0f; // reversed Z: push casters away from the sun
    terrainDesc.depthBiasSlope = -1.5f;
    terrainShadowPipeline_ = createGraphicsPipeline(ctx.device, terrainDesc, layout);

    if (atlas)
        vegetation_ = std::make_unique<VegetationRenderer>(ctx, scene, *atlas, plantPassFormats(), instanceCapacity);
    createShadowMap();
    skyPipeline_ = createGraphicsPipeline(ctx.device,
                                          {.vertexShader = "sky.vert",
                                           .fragmentShader = "sky.frag",
                                           .cullMode = VK_CULL_MODE_NONE,
                                           .colorFormats = {mainDesc.colors[0].format},
                                           .depthFormat = mainDesc.depthFormat,
                                           .depthWrite = false,
                                           .depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL,
                                           .samples = mainDesc.samples},
                                          layout);
}

SceneRenderer::~SceneRenderer() {
    ctx_.submitter.waitIdle();
    for (TileCoord coord : tiles()) removeTile(coord);
    releaseHorizonRing();
    vegetation_.reset();
    objects_.reset();
    tracks_.reset();
    shadowMap_.reset();
    vkDestroySampler(ctx_.vk(), shadowSampler_, nullptr);
    vkDestroySampler(ctx_.vk(), coverSampler_, nullptr);
    destroyImage(ctx_, groundTextures_);
    vkDestroySampler(ctx_.vk(), groundSampler_, nullptr);
    destroyPipeline(ctx_.device, terrainPipeline_);
    destroyPipeline(ctx_.device, terrainTruthPipeline_);
    destroyPipeline(ctx_.device, terrainTruthFlowPipeline_);
    destroyPipeline(ctx_.device, terrainShadowPipeline_);
    destroyPipeline(ctx_.device, skyPipeline_);
    destroyBuffer(ctx_, constants_);
}

void SceneRenderer::addTile(TileCoord coord, const Ground& ground, const VegetationTile* plants,
                            const CoverMap* cover) {
    require(!hasTile(coord), "SceneRenderer: the tile is resident already");
    TerrainTile tile;
    const GroundDrawMesh mesh = groundDrawMesh(ground);
    // Storage too: the truth pass pulls whole triangles (terrain_truth.vert).
    tile.vertices = createBufferWithData(ctx_, bytesOf(mesh.vertices),
                                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    tile.indices = createBufferWithData(ctx_, bytesOf(mesh.indices),
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    tile.indexCount = uint32_t(mesh.indices.size());
    tile.boundsMin = glm::dvec2(ground.boundsMin());
    tile.boundsMax = glm::dvec2(ground.boundsMax());
    uploadCoverMap(tile, plants && vegetation_ ? cover : nullptr);
    tiles_.emplace(TileKey(coord.y, coord.x), std::move(tile));
    if (plants && vegetation_ && !plants->fields.empty()) vegetation_->addTile(*plants);
}

std::vector<TileCoord> SceneRenderer::tiles() const {
    std::vector<TileCoord> coords;
    for (const auto& [key, tile] : tiles_) coords.push_back({key.second, key.first});
    return coords;
}

void SceneRenderer::removeTile(TileCoord coord) {
    auto it = tiles_.find(TileKey(coord.y, coord.x));
    if (it == tiles_.end()) return;
    retireBuffer(ctx_, it->second.vertices);
    retireBuffer(ctx_, it->second.indices);
    retireImage(ctx_, it->second.cover);
    retireImage(ctx_, it->second.groundWeights);
    tiles_.erase(it);
    if (vegetation_) vegetation_->removeTile(coord);
}

void SceneRenderer::writeConstants(uint32_t slot, const Camera& camera, const ShadowFit& shadow, double timeSeconds,
                                   int shadowDraw, const FlowTicks* flow, uint32_t view) {
    gpu::FrameConstants c = frameTemplate_;
    glm::dmat4 viewProj = camera.viewProjection();
    c.viewProj = glm::mat4(viewProj);
    c.view = glm::mat4(camera.view());
    c.invViewProj = glm::mat4(glm::inverse(viewProj));
    c.cameraPosition = glm::vec4(glm::vec3(camera.position), 1.0f);
    c.sunDirection = glm::vec4(scene_.sun.direction(), 0.0f);
    c.sunRadiance = glm::vec4(scene_.sun.radiance, 0.0f);
    c.viewport =
        glm::vec4(float(camera.width), float(camera.height), 1.0f / float(camera.width), 1.0f / float(camera.height));
    c.timeParams = glm::vec4(float(timeSeconds), 0.0f, 0.0f, 0.0f);

    // Sun shadows: the cascades fitted to the reference camera, the same for both views of a stereo pair.
    const std::vector<ShadowCascade>& cascades = shadow.cascades;
    const bool shadows = scene_.render.shadowMapSize > 0;
    const glm::uvec2 extent = shadowMapExtent(shadowParams_);
    c.shadowParams = glm::vec4(shadows ? float(cascades.size()) : 0.0f, 0.0f, 0.0f, 0.0f);
    for (size_t k = 0; k < cascades.size(); ++k) {
        c.shadowCascades[k] = glm::mat4(cascades[k].viewProj);
        c.shadowTiles[k] =
            glm::vec4(float(cascades[k].mapOffset) / float(extent.x), float(cascades[k].mapSize) / float(extent.x),
                      float(cascades[k].mapSize) / float(extent.y), 1.0f / float(cascades[k].mapSize));
        c.shadowEnds[int(k)] = float(cascades[k].end);
        c.shadowBias[int(k)] = float(cascades[k].depthBias);
    }
    c.shadowOrigin = glm::vec4(glm::vec3(shadow.origin), 1.0f);
    if (shadowDraw >= 0) {
        const ShadowCascade& drawn = cascades[size_t(shadowDraw)];
        const double reach = shadowParams_.casterMargin;
        c.shadowViewProj = c.shadowCascades[shadowDraw];
        c.shadowParams.y = float(std::max(drawn.firstReceiver - reach, 0.0));
        c.shadowParams.z = float(drawn.end + reach);
        if (vegetation_) c.shadowParams.w = float(vegetation_->shadowAtlasLevel(2.0 * drawn.radius / drawn.mapSize));
    }
    c.debug = glm::uvec4(debugFlags_, 0u, 0u, 0u);
    c.coverBand = glm::vec4(scene_.lod.farLimit, scene_.lod.band, scene_.lod.midToFar,
                            horizon_ ? float(viewDistance_) : 0.0f); // the ground disc (horizon_ring.glsl)
    if (flow) {
        c.viewProjPrevious = glm::mat4(flow->previous[view]->viewProjection());
        c.viewProjNext = glm::mat4(flow->next[view]->viewProjection());
        c.flowReferencePrevious = glm::vec4(glm::vec3(flow->previous[0]->position), 1.0f);
        c.flowReferenceNext = glm::vec4(glm::vec3(flow->next[0]->position), 1.0f);
        c.flowTimes = glm::vec4(float(timeSeconds - flow->timeStep), float(timeSeconds + flow->timeStep), 0.0f, 0.0f);
        c.flowParams = glm::uvec4(objects_ ? objects_->transformCount() : 0u, 0u, 0u, 0u);
    }
    std::memcpy(constants_.mapped() + slot * constantsStride_, &c, sizeof c);
}

void SceneRenderer::drawTerrain(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame,
                                const glm::dvec3& reference) {
    // With ruts the ground has holes where their patches lie (render/track_renderer.h); not in the shadow pass.
    const bool ruts = tracks_ && tracks_->active() && pass != PlantPass::Shadow;
    const bool truth = pass == PlantPass::Truth || pass == PlantPass::TruthFlow;
    const Pipeline& pipeline = ruts                           ? tracks_->holedGround(pass)
                               : pass == PlantPass::Main      ? terrainPipeline_
                               : pass == PlantPass::Truth     ? terrainTruthPipeline_
                               : pass == PlantPass::TruthFlow ? terrainTruthFlowPipeline_
                                                              : terrainShadowPipeline_;
    bindPipeline(cmd, pipeline);
    const DescriptorBinding textures = sampledImage(gpu::kBindingGroundTextures, groundTextures_.view, groundSampler_);
    uint32_t drawn = 0; // the tile's index among those drawn (TrackRenderer::update's tiles)
    for (const auto& [key, tile] : tiles_) {
        if (!tileDrawn(tile, reference)) continue;
        const uint32_t tileIndex = drawn++;
        if (ruts && tileIndex > 0) bindPipeline(cmd, pipeline); // the previous tile's patches bound their own
        const DescriptorBinding cover = sampledImage(gpu::kBindingCoverMap, tile.cover.view, coverSampler_);
        const DescriptorBinding weights =
            sampledImage(gpu::kBindingGroundMaterials, tile.groundWeights.view, coverSampler_);
        gpu::TerrainTileConstants constants{.coverRect = tile.coverRect, .material = groundMaterialConstants(scene_)};
        constants.material.y &= uint32_t(tile.groundMaterials);
        if (pass == PlantPass::Main) {
            if (ruts)
                pushDescriptors(ctx_.device, cmd, pipeline,
                                {frame, shadowBinding(), cover, textures, weights, tracks_->tableBinding()});
            else
                pushDescriptors(ctx_.device, cmd, pipeline, {frame, shadowBinding(), cover, textures, weights});
            pushConstants(cmd, pipeline, constants);
        } else if (truth) {
            const DescriptorBinding vertices = storageBuffer(gpu::kBindingMeshVertices, tile.vertices.handle);
            const DescriptorBinding indices = storageBuffer(gpu::kBindingMeshIndices, tile.indices.handle);
            if (ruts)
                pushDescriptors(ctx_.device, cmd, pipeline, {frame, vertices, indices, cover, tracks_->tableBinding()});
            else
                pushDescriptors(ctx_.device, cmd, pipeline, {frame, vertices, indices, cover});
            pushConstants(cmd, pipeline, constants);
            vkCmdDraw(cmd, tile.indexCount, 1, 0, 0); // non-indexed: the shader reads the triangle list
        } else {
            pushDescriptors(ctx_.device, cmd, pipeline, {frame});
        }
        if (!truth) {
            VkDeviceSize offset = 0;
            vkCmdBindVertexBuffers(cmd, 0, 1, &tile.vertices.handle, &offset);
            vkCmdBindIndexBuffer(cmd, tile.indices.handle, 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd, tile.indexCount, 1, 0, 0, 0);
        }
        if (!ruts) continue; // ruts: the patches overlapping this tile, with its cover
        if (pass == PlantPass::Main)
            tracks_->drawMain(cmd, frame, shadowBinding(), cover, textures, weights, constants, tileIndex);
        else
            tracks_->drawTruth(cmd, frame, cover, constants, pass == PlantPass::TruthFlow, tileIndex);
    }
    if (horizon_ && pass != PlantPass::Shadow) drawHorizonRing(cmd, pass, frame); // beyond the shadow cascades
}

bool SceneRenderer::tileDrawn(const TerrainTile& tile, const glm::dvec3& reference) const {
    const double dx = std::max({0.0, tile.boundsMin.x - reference.x, reference.x - tile.boundsMax.x});
    const double dy = std::max({0.0, tile.boundsMin.y - reference.y, reference.y - tile.boundsMax.y});
    return std::sqrt(dx * dx + dy * dy) <= viewDistance_;
}

void SceneRenderer::setGroundTracks(const GroundTracks* tracks, const Ground* ground) {
    if (tracks_) tracks_->setSource(tracks, ground);
}

void SceneRenderer::setWorldGroundTracks(const GroundTracks* tracks) {
    if (tracks_) tracks_->setWorldSource(tracks, scene_);
}

glm::uvec4 groundMaterialConstants(const Scene& scene) {
    const uint32_t terrain = scene.terrain.material;
    glm::uvec4 material(terrain, 0u, 0u, 0u);
    for (uint32_t c = 0; c < scene.vegetation.categoryCount; ++c) {
        const int32_t own = scene.vegetation.categories[c].groundMaterial; // same order as gpu::kGroundMaterial*
        const uint32_t preset = own == kNoGroundMaterial ? terrain : uint32_t(own);
        material.y |= uint32_t(preset != terrain);
        material.z |= preset << (8 * c);
    }
    return material;
}

// Half floats: linear filtering of 16-bit float textures is mandatory in Vulkan, of 32-bit ones is not.
// The ground material weights likewise, beside it (1x1 zero without: lavapipe needs every binding written).
void SceneRenderer::uploadCoverMap(TerrainTile& tile, const CoverMap* cover) {
    const bool present = cover && !cover->texels.empty();
    const auto upload = [&](const std::vector<glm::vec4>* source) {
        const uint32_t width = source ? cover->width : 1, height = source ? cover->height : 1;
        std::vector<uint16_t> texels(size_t(width) * height * 4, 0);
        if (source)
            for (size_t i = 0; i < source->size(); ++i)
                for (int k = 0; k < 4; ++k) texels[4 * i + size_t(k)] = floatToHalfBits((*source)[i][k]);
        const std::span<const uint8_t> bytes = bytesOf(texels);
        return createImageWithData(
            ctx_, {.format = VK_FORMAT_R16G16B16A16_SFLOAT, .width = width, .height = height, .mipLevels = 1},
            {&bytes, 1});
    };
    tile.cover = upload(present ? &cover->texels : nullptr);
    tile.groundMaterials = present && !cover->groundWeights.empty();
    tile.groundWeights = upload(tile.groundMaterials ? &cover->groundWeights : nullptr);
    tile.coverRect = present ? glm::vec4(cover->origin, 1.0f / cover->size, 0.0f) : glm::vec4(0.0f);
}

// glTF's default wrap mode is repeat; per-texture samplers are not read (one sampler for the whole array).
void SceneRenderer::uploadGroundTextures(const Ground* terrain) {
    const GroundTextureArray textures = terrain ? groundTextureArray(*terrain) : groundTextureArray(Ground());
    std::vector<std::span<const uint8_t>> levels(textures.levels.begin(), textures.levels.end());
    groundTextures_ = createImageWithData(ctx_,
                                          {.format = VK_FORMAT_R8G8B8A8_SRGB,
                                           .width = textures.size,
                                           .height = textures.size,
                                           .mipLevels = textures.mipLevels,
                                           .layers = textures.layers},
                                          levels);
    groundSampler_ = createLinearSampler(ctx_, textures.mipLevels, VK_SAMPLER_ADDRESS_MODE_REPEAT);
}

DescriptorBinding SceneRenderer::frameBinding(uint32_t slot) const {
    return uniformBuffer(gpu::kBindingFrame, constants_.handle, slot * constantsStride_, sizeof(gpu::FrameConstants));
}

DescriptorBinding SceneRenderer::shadowBinding() const {
    return sampledImage(gpu::kBindingShadowMap, shadowMap_->depth().view, shadowSampler_,
                        VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
}

void SceneRenderer::recordMainPass(VkCommandBuffer cmd, RenderTarget& main, uint32_t frameSlot, uint32_t slot,
                                   const glm::dvec3& reference, GpuTimers* timers, const BakedPlants* baked) {
    DescriptorBinding frame = frameBinding(frameSlot), shadow = shadowBinding();
    if (timers) timers->begin(cmd, "main");
    main.begin(cmd);
    // Objects and plants first, the ground after them: the ground's samples they hide fail the early depth test
    // and are never shaded (the turf and far-cover shading is the main pass's most expensive per fragment).
    if (objects_) objects_->recordMain(cmd, frame, shadow, slot);
    if (vegetation_ && baked)
        vegetation_->drawBaked(cmd, *baked, frame, shadow, slot);
    else if (vegetation_)
        vegetation_->draw(cmd, PlantPass::Main, frame, shadow, slot);
    drawTerrain(cmd, PlantPass::Main, frame, reference);
    // Sky last: the depth test (GREATER_OR_EQUAL against the far-plane clear) shades only uncovered pixels.
    bindPipeline(cmd, skyPipeline_);
    pushDescriptors(ctx_.device, cmd, skyPipeline_, {frame});
    vkCmdDraw(cmd, 3, 1, 0, 0);
    if (overlay_) overlay_(cmd, frame);
    if (timers) timers->end(cmd);
    if (timers) timers->begin(cmd, "resolve");
    main.end(cmd);
    if (timers) timers->end(cmd);
}

void SceneRenderer::record(VkCommandBuffer cmd, RenderTarget& main, RenderTarget* truth, const Camera& camera,
                           double timeSeconds, uint32_t frameIndex, GpuTimers* timers) {
    View view{&camera, &main, truth};
    recordViews(cmd, {&view, 1}, timeSeconds, frameIndex, timers);
}

void SceneRenderer::recordExpansion(VkCommandBuffer cmd, std::span<const View> views, double timeSeconds,
                                    uint32_t frameIndex, GpuTimers* timers) {
    require(!views.empty() && views.size() <= kMaxViews, "a frame has one or two views");
    if (!vegetation_) return;
    const Camera& reference = *views[0].camera;
    if (timers) timers->begin(cmd, "expansion");
    std::array<glm::vec4, 5> planes =
        views.size() == 2 ? stereoFrustumPlanes(reference, *views[1].camera) : reference.frustumPlanes();
    vegetation_->expand(cmd, reference, timeSeconds, frameIndex % gpu::kFrameDataSlots, &planes);
    if (timers) timers->end(cmd);
}

void SceneRenderer::recordViews(VkCommandBuffer cmd, std::span<const View> views, double timeSeconds,
                                uint32_t frameIndex, GpuTimers* timers, bool expand, const FlowTicks* flow) {
    require(!views.empty() && views.size() <= kMaxViews, "a frame has one or two views");
    const Camera& reference = *views[0].camera;
    const uint32_t dataSlot = frameIndex % gpu::kFrameDataSlots; // objects' and vegetation's per-frame data
    const uint32_t firstSlot = dataSlot * kSlotsPerFrame;        // frame constants: views, then shadow cascades
    const ShadowFit shadowFit = fitShadows(reference); // once per frame: both views and every cascade's draw use it
    for (uint32_t v = 0; v < views.size(); ++v)
        writeConstants(firstSlot + v, *views[v].camera, shadowFit, timeSeconds, -1, flow, v);
    const DescriptorBinding shadow = shadowBinding();
    const std::array<double, 2> flowTimes{timeSeconds - (flow ? flow->timeStep : 0.0),
                                          timeSeconds + (flow ? flow->timeStep : 0.0)};
    if (objects_) objects_->update(timeSeconds, dataSlot, flow ? &flowTimes : nullptr);
    if (tracks_) {
        ScopedGpuTimer timed(timers, cmd, "tracks"); // the ruts' uploads: every pass is timed (docs/release.md)
        // A world draws each patch with every drawn tile it overlaps (drawTerrain's tiles, in its order).
        std::vector<TrackTileRect> drawn;
        for (const auto& [key, tile] : tiles_)
            if (world() && tileDrawn(tile, reference.position)) drawn.push_back({tile.boundsMin, tile.boundsMax});
        tracks_->update(cmd, reference,
                        views.size() == 2 ? stereoFrustumPlanes(reference, *views[1].camera)
                                          : reference.frustumPlanes(),
                        dataSlot, world() ? std::span<const TrackTileRect>(drawn) : TrackRenderer::kOneTile);
    }

    if (expand) recordExpansion(cmd, views, timeSeconds, frameIndex, timers);

    recordShadowPass(cmd, reference, shadowFit, firstSlot, dataSlot, timeSeconds, timers);

    for (uint32_t v = 0; v < views.size(); ++v)
        if (views[v].main) // null: the truth of a frame whose colour comes from an exposure's sub-frames
            recordMainPass(cmd, *views[v].main, firstSlot + v, dataSlot, reference.position, timers, nullptr);
    if (flow && flow->beforeTruth) {
        ScopedGpuTimer timed(timers, cmd, "flow");
        flow->beforeTruth(cmd);
        computeToVertexAndCopyBarrier(cmd); // the next tick's plant states -> the truth pass's vertex shaders
    }
    const PlantPass truthPass = flow ? PlantPass::TruthFlow : PlantPass::Truth;
    for (uint32_t v = 0; v < views.size(); ++v) {
        const uint32_t slot = firstSlot + v;
        if (!views[v].truth) continue;
        if (timers) timers->begin(cmd, "truth");
        views[v].truth->begin(cmd);
        // The main pass's order (recordMainPass): a depth tie resolves alike in both, and the ground's fragments
        // behind plants and objects fail the early depth test.
        if (objects_) objects_->recordTruth(cmd, frameBinding(slot), dataSlot, flow != nullptr);
        if (vegetation_) vegetation_->draw(cmd, truthPass, frameBinding(slot), shadow, dataSlot);
        drawTerrain(cmd, truthPass, frameBinding(slot), reference.position);
        views[v].truth->end(cmd);
        if (timers) timers->end(cmd);
    }
}

void SceneRenderer::recordMainOnly(VkCommandBuffer cmd, RenderTarget& main, const Camera& camera, double timeSeconds,
                                   uint32_t frameIndex, GpuTimers* timers, const BakedPlants* baked) {
    const uint32_t slot = frameIndex % gpu::kFrameDataSlots;
    writeConstants(slot * kSlotsPerFrame, camera, fitShadows(camera), timeSeconds);
    if (objects_) objects_->update(timeSeconds, slot);
    if (vegetation_ && !baked) {
        if (timers) timers->begin(cmd, "expansion");
        vegetation_->expand(cmd, camera, timeSeconds, slot);
        if (timers) timers->end(cmd);
    }
    recordMainPass(cmd, main, slot * kSlotsPerFrame, slot, camera.position, timers, baked);
}

} // namespace sward
