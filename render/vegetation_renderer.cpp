#include "render/vegetation_renderer.h"

#include "engine/barriers.h"
#include "vegetation/atlas_cutout.h"

#include "shared/plant_blades.h"

#include <algorithm>
#include <cstring>

namespace sward {

namespace {

constexpr VkShaderStageFlags kDrawStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
constexpr VkBufferUsageFlags kStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

// Set 0 of every plant draw (expanded or baked): frame and vegetation constants, the instances (or baked
// vertices), the atlas cell table and the atlas.
std::vector<VkDescriptorSetLayoutBinding> plantDrawBindings() {
    return {layoutBinding(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kDrawStages),
            layoutBinding(gpu::kBindingVegetation, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kDrawStages),
            layoutBinding(gpu::kBindingPlantInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kDrawStages),
            layoutBinding(gpu::kBindingAtlasCells, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kDrawStages),
            // The blades' vertex shader reads their colour from the atlas too (plant_blade.vert).
            layoutBinding(gpu::kBindingAtlas, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kDrawStages)};
}

VkDescriptorSetLayoutBinding shadowMapLayoutBinding() {
    return layoutBinding(gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                         VK_SHADER_STAGE_FRAGMENT_BIT);
}

} // namespace

uint32_t VegetationRenderer::instanceCapacityFor(uint64_t plants) {
    return uint32_t(std::clamp<uint64_t>(plants * 2, 1024, 4u << 20));
}

uint32_t VegetationRenderer::shadowAtlasLevel(double texelMetres) const {
    double shortest = INFINITY;
    for (uint32_t i = 0; i < scene_.vegetation.categoryCount; ++i)
        shortest = std::min(shortest, double(scene_.vegetation.categories[i].height));
    return atlasLevelForTexel(atlasCellHeight_, atlasLevels_, shortest, texelMetres);
}

VegetationRenderer::Tile::Tile(Context& ctx, const VegetationTile& tile, uint64_t constantsBytes)
    : ctx(ctx), coord(tile.coord), boundsMin(glm::dvec2(tile.origin)),
      boundsMax(glm::dvec2(tile.origin) + double(tile.size)), buffers(ctx, tile) {
    constants = createBuffer(ctx, constantsBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryIntent::Upload);
    clusterCounts = createBuffer(ctx, uint64_t(std::max(buffers.clusterCount, 1u)) * 16, kStorage,
                                 MemoryIntent::DeviceLocal);
    draws = createBuffer(ctx, (gpu::kLodCount + 1) * sizeof(VkDrawIndexedIndirectCommand), // + the near blades
                         kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, MemoryIntent::DeviceLocal);
    stats = createBuffer(ctx, sizeof(gpu::ExpansionStats), kStorage, MemoryIntent::DeviceLocal);
    clusterBoxes = sward::clusterBoxes(tile);
    const uint64_t align = ctx.device.properties().limits.minStorageBufferOffsetAlignment;
    orderStride = (uint64_t(std::max(buffers.clusterCount, 1u)) * sizeof(uint32_t) + align - 1) / align * align;
    clusterOrder = createBuffer(ctx, orderStride * gpu::kFrameDataSlots, kStorage, MemoryIntent::Upload);
}

VegetationRenderer::Tile::~Tile() {
    for (Buffer* b : {&constants, &clusterCounts, &draws, &stats, &clusterOrder, &keptStates[0], &keptStates[1]})
        if (b->handle) retireBuffer(ctx, *b);
}

PipelineLayoutDesc VegetationRenderer::drawLayout(bool withShadowMap) const {
    std::vector<VkDescriptorSetLayoutBinding> bindings = plantDrawBindings();
    bindings.push_back(
        layoutBinding(gpu::kBindingInstancePlants, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT));
    if (withShadowMap) bindings.push_back(shadowMapLayoutBinding());
    return {.bindings = bindings, .pushConstantSize = sizeof(uint32_t), .pushConstantStages = kDrawStages}; // lod
}

GraphicsPipelineDesc VegetationRenderer::mainPipelineDesc(const char* fragmentShader, bool farBillboards) const {
    const bool msaa = formats_.mainSamples != VK_SAMPLE_COUNT_1_BIT;
    return {
        .vertexShader = "plant.vert",
        .fragmentShader = fragmentShader,
        .cullMode = VK_CULL_MODE_NONE, // quads are seen from both sides
        .colorFormats = {formats_.mainColor},
        .depthFormat = formats_.mainDepth,
        .samples = formats_.mainSamples,
        .alphaToCoverage = msaa,
        .specialization = {/* PASS= */ gpu::kPassMain, /* ALPHA_TO_COVERAGE= */ msaa ? 1u : 0u,
                           /* FAR_BILLBOARDS= */ farBillboards ? 1u : 0u},
    };
}

VegetationRenderer::VegetationRenderer(Context& ctx, const Scene& scene, const Atlas& atlas,
                                       const VegetationPassFormats& formats, uint32_t instanceCapacity)
    : ctx_(ctx), scene_(scene), capacity_(std::max(instanceCapacity, 1u)), formats_(formats) {
    require(atlas.desc.rows.size() >= scene.vegetation.categoryCount,
            "the atlas has " + std::to_string(atlas.desc.rows.size()) + " rows but the scene has " +
                std::to_string(scene.vegetation.categoryCount) + " vegetation categories");
    uint64_t align = ctx.device.properties().limits.minUniformBufferOffsetAlignment;
    constantsStride_ = (sizeof(gpu::VegetationConstants) + align - 1) / align * align;
    instances_ = createBuffer(ctx, uint64_t(capacity_) * sizeof(gpu::ExpandedPlant), kStorage, MemoryIntent::DeviceLocal);
    instancePlants_ = createBuffer(ctx, uint64_t(capacity_) * sizeof(uint32_t), kStorage, MemoryIntent::DeviceLocal);
    cursor_ = createBuffer(ctx, 16, kStorage, MemoryIntent::DeviceLocal);
    uploadAtlas(atlas);

    auto ssbo = [](uint32_t b, VkShaderStageFlags stages) {
        return layoutBinding(b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages);
    };
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    PipelineLayoutDesc expandLayout{
        .bindings = {ssbo(gpu::kExpandBindingStatics, cs),
                     layoutBinding(gpu::kBindingVegetation, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs),
                     ssbo(gpu::kExpandBindingDynamics, cs), ssbo(gpu::kExpandBindingClusters, cs),
                     ssbo(gpu::kExpandBindingFields, cs), ssbo(gpu::kExpandBindingClusterCounts, cs),
                     ssbo(gpu::kExpandBindingInstances, cs), ssbo(gpu::kExpandBindingInstancePlants, cs)}};
    countPipeline_ = createComputePipeline(ctx.device, "vegetation_expand.comp", expandLayout, {/* WRITE_PASS= */ 0});
    writePipeline_ = createComputePipeline(ctx.device, "vegetation_expand.comp", expandLayout, {/* WRITE_PASS= */ 1});
    // The scan is one workgroup of kScanGroupSize lanes sharing a uvec4 per lane and a counter: more than the 128
    // invocations and 16384 bytes Vulkan guarantees (every desktop GPU has 1024 and 32 KiB).
    ctx.device.requireComputeWorkgroup("vegetation_scan.comp", gpu::kScanGroupSize,
                                       gpu::kScanGroupSize * 4 * sizeof(uint32_t) + sizeof(uint32_t));
    scanPipeline_ =
        createComputePipeline(ctx.device, "vegetation_scan.comp",
                              {.bindings = {ssbo(gpu::kScanBindingClusterCounts, cs), ssbo(gpu::kScanBindingDraws, cs),
                                            ssbo(gpu::kScanBindingStats, cs), ssbo(gpu::kScanBindingCursor, cs),
                                            ssbo(gpu::kScanBindingClusterOrder, cs)},
                               .pushConstantSize = sizeof(gpu::ScanConstants),
                               .pushConstantStages = cs});

    PipelineLayoutDesc shadowLayout = drawLayout(false);
    mainPipeline_ = createGraphicsPipeline(ctx.device, mainPipelineDesc("plant.frag", false), drawLayout(true));
    GraphicsPipelineDesc plants = mainPipelineDesc("plant.frag");
    mainFarPipeline_ = createGraphicsPipeline(ctx.device, plants, drawLayout(true));
    truthPipeline_ = createGraphicsPipeline(ctx.device, truthPipelineDesc(), shadowLayout);
    plants.samples = VK_SAMPLE_COUNT_1_BIT;
    plants.alphaToCoverage = false;
    plants.fragmentShader = "plant_shadow.frag";
    plants.colorFormats = {};
    plants.depthFormat = formats.shadowDepth;
    plants.specialization = {/* PASS= */ gpu::kPassShadow, /* ALPHA_TO_COVERAGE= */ 0};
    plants.depthBias = -1.0f; // reversed Z: push casters away from the sun
    plants.depthBiasSlope = -1.5f;
    shadowPipeline_ = createGraphicsPipeline(ctx.device, plants, shadowLayout);
}

VegetationRenderer::~VegetationRenderer() {
    ctx_.submitter.waitIdle();
    tiles_.clear();
    for (Pipeline* p : {&countPipeline_, &scanPipeline_, &writePipeline_, &mainPipeline_, &mainFarPipeline_,
                        &truthPipeline_, &truthFlowPipeline_, &shadowPipeline_, &bakePipeline_, &staticPipeline_,
                        &floorPipeline_})
        destroyPipeline(ctx_.device, *p);
    for (Pipeline& p : bladePipelines_) destroyPipeline(ctx_.device, p);
    for (Buffer* b : {&instances_, &instancePlants_, &cursor_, &atlasCells_, &cornerIndices_}) destroyBuffer(ctx_, *b);
    destroyImage(ctx_, atlasImage_);
    vkDestroySampler(ctx_.vk(), atlasSampler_, nullptr);
}

void VegetationRenderer::uploadAtlas(const Atlas& atlas) {
    require(!atlas.mips.empty(), "the atlas has no image");
    const AtlasDesc& desc = atlas.desc;
    uint32_t maxColumns = desc.maxColumns();
    atlasMaxColumns_ = maxColumns;
    for (uint32_t r = 0; r < std::min<size_t>(desc.rows.size(), 4); ++r) atlasColumns_[int(r)] = uint32_t(desc.rows[r].cells.size());
    const std::array<float, 4> cover = cardCover(atlas);
    cardCover_ = glm::vec4(cover[0], cover[1], cover[2], cover[3]);
    const std::array<float, 4> aspects = meanAspects(desc);
    meanAspects_ = glm::vec4(aspects[0], aspects[1], aspects[2], aspects[3]);
    atlasCellHeight_ = desc.cellHeight;
    atlasLevels_ = uint32_t(atlas.mips.size());
    std::vector<gpu::AtlasCellGpu> cells(desc.rows.size() * maxColumns);
    for (uint32_t r = 0; r < desc.rows.size(); ++r)
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c) {
            auto uv = desc.cellUvRect(r, c);
            const AtlasCell& cell = desc.rows[r].cells[c];
            cells[r * maxColumns + c] = {glm::vec4(uv[0], uv[1], uv[2], uv[3]),
                                         glm::vec4(cell.baseU, cell.baseV, cell.aspect, 0.0f), {}};
        }
    // Whole quads only: cut-out polygons are fitted by setCutout when a caller asks for them (they are off by
    // default, and fitting every corner count costs more than the rest of the upload).
    const CutoutPolygon full = fullCellPolygon();
    cellTables_[0] = cells;
    for (gpu::AtlasCellGpu& cell : cellTables_[0])
        for (uint32_t k = 0; k < gpu::kMaxCutoutCorners / 2; ++k)
            cell.cutout[k] = glm::vec4(full.corners[2 * k], full.corners[2 * k + 1]);
    uploadCutoutBuffers();

    const uint32_t levels = uint32_t(atlas.mips.size());
    std::vector<std::span<const uint8_t>> data;
    for (const AtlasMip& mip : atlas.mips) data.push_back(mip.rgba);
    atlasImage_ = createImageWithData(
        ctx_, {.format = VK_FORMAT_R8G8B8A8_SRGB, .width = atlas.mips[0].width, .height = atlas.mips[0].height,
               .mipLevels = levels},
        data);

    atlasSampler_ = createLinearSampler(ctx_, levels);
}

void VegetationRenderer::uploadCutoutBuffers() {
    const std::vector<gpu::AtlasCellGpu>& table = cellTables_[cutoutCorners_];
    // Frames in flight may still read the old buffers.
    for (Buffer* b : {&atlasCells_, &cornerIndices_})
        if (b->handle) retireBuffer(ctx_, *b);
    atlasCells_ = createBufferWithData(ctx_, bytesOf(table), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::vector<uint32_t> corners;
    for (uint32_t lod = 0; lod < gpu::kLodCount; ++lod)
        for (uint32_t k = 0; k < gpu::plantVertexCount(lod, cutoutCorners_); ++k)
            corners.push_back(gpu::plantIndex(lod, cutoutCorners_, k));
    for (uint32_t k = 0; k < gpu::kMaxNearBlades * gpu::kBladeIndices; ++k) corners.push_back(gpu::bladeIndex(k));
    cornerIndices_ = createBufferWithData(ctx_, bytesOf(corners), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
}

void VegetationRenderer::setCutout(uint32_t corners, const Atlas& atlas) {
    require(corners == 0 || (corners >= 4 && corners <= gpu::kMaxCutoutCorners), "cut-outs have 4..8 corners (0: off)");
    if (corners == cutoutCorners_) return;
    std::vector<gpu::AtlasCellGpu>& table = cellTables_[corners];
    if (table.empty()) { // fitted once per corner count, then switching costs only an upload
        const std::vector<CutoutPolygon> polygons = atlasCutouts(atlas, corners);
        require(polygons.size() == cellTables_[0].size(), "setCutout: not the atlas this renderer was made with");
        table = cellTables_[0];
        for (size_t i = 0; i < table.size(); ++i)
            for (uint32_t k = 0; k < gpu::kMaxCutoutCorners / 2; ++k)
                table[i].cutout[k] = glm::vec4(polygons[i].corners[2 * k], polygons[i].corners[2 * k + 1]);
    }
    cutoutCorners_ = corners;
    uploadCutoutBuffers();
}

DescriptorBinding VegetationRenderer::atlasCellsBinding() const {
    return storageBuffer(gpu::kBindingAtlasCells, atlasCells_.handle);
}

DescriptorBinding VegetationRenderer::atlasBinding() const {
    return sampledImage(gpu::kBindingAtlas, atlasImage_.view, atlasSampler_);
}

DescriptorBinding VegetationRenderer::constantsBinding(const Tile& tile, uint32_t slot) const {
    return uniformBuffer(gpu::kBindingVegetation, tile.constants.handle, (slot % gpu::kFrameDataSlots) * constantsStride_,
                         sizeof(gpu::VegetationConstants));
}

void VegetationRenderer::addTile(const VegetationTile& tile) {
    require(!hasTile(tile.coord), "VegetationRenderer: the tile is resident already");
    const auto [it, added] =
        tiles_.emplace(TileKey(tile.coord.y, tile.coord.x),
                       std::make_unique<Tile>(ctx_, tile, constantsStride_ * gpu::kFrameDataSlots));
    if (truthFlowPipeline_.handle) startKeptStates(*it->second); // a world's tile made resident with flow on
}

void VegetationRenderer::removeTile(TileCoord coord) {
    tiles_.erase(TileKey(coord.y, coord.x));
}

bool VegetationRenderer::hasTile(TileCoord coord) const {
    return tiles_.contains(TileKey(coord.y, coord.x));
}

VegetationRenderer::Tile& VegetationRenderer::onlyTile() {
    require(tiles_.size() == 1, "VegetationRenderer: this needs exactly one resident tile");
    return *tiles_.begin()->second;
}

VegetationBuffers& VegetationRenderer::buffers() {
    return onlyTile().buffers;
}

VegetationBuffers& VegetationRenderer::buffers(TileCoord coord) {
    const auto it = tiles_.find(TileKey(coord.y, coord.x));
    require(it != tiles_.end(), "VegetationRenderer: tile (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) +
                                    ") is not resident");
    return it->second->buffers;
}

void VegetationRenderer::writeConstants(const Tile& tile, const Camera& camera, double timeSeconds, uint32_t slot,
                                        const std::array<glm::vec4, 5>& planes) {
    gpu::VegetationConstants c{};
    for (int i = 0; i < 5; ++i) c.frustumPlanes[i] = planes[i];
    c.cameraPosition = glm::vec4(glm::vec3(camera.position), 1.0f);
    c.lodDistances = glm::vec4(scene_.lod.nearToMid, scene_.lod.midToFar, scene_.lod.farLimit, scene_.lod.band);
    glm::vec2 dir = scene_.wind.direction();
    c.wind = glm::vec4(dir, scene_.wind.strength, scene_.wind.gustFrequency);
    c.windGusts = glm::vec4(scene_.wind.gustStrength, scene_.wind.gustWavelength, float(timeSeconds), scene_.wind.flutter);
    for (uint32_t i = 0; i < gpu::kMaxPlantCategories; ++i) c.categoryHeight[int(i)] = scene_.vegetation.categories[i].height;
    c.atlasColumns = atlasColumns_;
    c.counts = glm::uvec4(tile.buffers.clusterCount, tile.buffers.clustersPerField, capacity_, atlasMaxColumns_);
    const WorldParams& w = scene_.world;
    if (w.enabled && w.tilesX * w.tilesY > 1)
        c.tile = glm::uvec4(uint32_t(tile.coord.y) * w.tilesX + uint32_t(tile.coord.x) + 1u, 0u, 0u, 0u);
    c.options = glm::uvec4(cutoutCorners_, scene_.lod.nearBlades, scene_.lod.nearBlades ? bladeCategories() : 0u, 0u);
    c.categoryCard = cardCover_;
    c.categoryAspect = meanAspects_;
    c.farLod = glm::vec4(scene_.lod.sliceLayers, scene_.lod.mergeWidth, float(camera.fy), scene_.lod.depthMerge);
    std::memcpy(tile.constants.mapped() + (slot % gpu::kFrameDataSlots) * constantsStride_, &c, sizeof c);
    frontToBack(tile.clusterBoxes, glm::vec3(camera.position), orderScratch_);
    std::memcpy(tile.clusterOrder.mapped() + (slot % gpu::kFrameDataSlots) * tile.orderStride, orderScratch_.data(),
                orderScratch_.size() * sizeof(uint32_t));
}

void VegetationRenderer::expand(VkCommandBuffer cmd, const Camera& camera, double timeSeconds, uint32_t slot,
                                const std::array<glm::vec4, 5>* cullPlanes) {
    const std::array<glm::vec4, 5> planes = cullPlanes ? *cullPlanes : camera.frustumPlanes();
    // The previous frame's draws read instances and draw commands; this frame overwrites them (WAR).
    drawReadsToComputeWritesBarrier(cmd);
    bool first = true;
    for (const auto& [key, tile] : tiles_) {
        tile->expanded = withinReach(*tile, camera.position);
        if (!tile->expanded) continue;
        writeConstants(*tile, camera, timeSeconds, slot, planes);
        expandTile(cmd, *tile, slot, first);
        first = false;
    }
    computeToDrawBarrier(cmd);
}

// A plant is drawn while its root is nearer than lod.far + half the band (chooseLod, 3D distance); the roots of a tile
// lie in its square, so a tile whose square is farther in xy (plus a metre for float rounding) adds no instance: it
// is skipped, and a resident tile out of reach costs nothing per frame.
bool VegetationRenderer::withinReach(const Tile& tile, const glm::dvec3& camera) const {
    const double dx = std::max({0.0, tile.boundsMin.x - camera.x, camera.x - tile.boundsMax.x});
    const double dy = std::max({0.0, tile.boundsMin.y - camera.y, camera.y - tile.boundsMax.y});
    const double reach = double(scene_.lod.farLimit) + 0.5 * double(scene_.lod.band) + 1.0;
    return dx * dx + dy * dy < reach * reach;
}

void VegetationRenderer::expandTile(VkCommandBuffer cmd, const Tile& tile, uint32_t slot, bool firstTile) {
    const VegetationBuffers& b = tile.buffers;
    auto bindExpand = [&](const Pipeline& pipeline) {
        bindPipeline(cmd, pipeline);
        pushDescriptors(ctx_.device, cmd, pipeline,
                        {storageBuffer(gpu::kExpandBindingStatics, b.statics.handle), constantsBinding(tile, slot),
                         storageBuffer(gpu::kExpandBindingDynamics, b.dynamics.handle),
                         storageBuffer(gpu::kExpandBindingClusters, b.clusters.handle),
                         storageBuffer(gpu::kExpandBindingFields, b.fields.handle),
                         storageBuffer(gpu::kExpandBindingClusterCounts, tile.clusterCounts.handle),
                         storageBuffer(gpu::kExpandBindingInstances, instances_.handle),
                         storageBuffer(gpu::kExpandBindingInstancePlants, instancePlants_.handle)});
    };

    // Count and write passes: one invocation per cluster.
    bindExpand(countPipeline_);
    dispatchLinear(cmd, b.clusterCount, gpu::kExpandGroupSize);
    computeToComputeBarrier(cmd);

    bindPipeline(cmd, scanPipeline_);
    pushDescriptors(ctx_.device, cmd, scanPipeline_,
                    {storageBuffer(gpu::kScanBindingClusterCounts, tile.clusterCounts.handle),
                     storageBuffer(gpu::kScanBindingDraws, tile.draws.handle),
                     storageBuffer(gpu::kScanBindingStats, tile.stats.handle),
                     storageBuffer(gpu::kScanBindingCursor, cursor_.handle),
                     storageBuffer(gpu::kScanBindingClusterOrder, tile.clusterOrder.handle,
                                   (slot % gpu::kFrameDataSlots) * tile.orderStride, tile.orderStride)});
    pushConstants(cmd, scanPipeline_,
                  gpu::ScanConstants{.clusterCount = b.clusterCount,
                                     .capacity = capacity_,
                                     .firstTile = firstTile ? 1u : 0u,
                                     .cutoutCorners = cutoutCorners_,
                                     .nearBlades = scene_.lod.nearBlades});
    vkCmdDispatch(cmd, 1, 1, 1); // one workgroup scans every cluster
    computeToComputeBarrier(cmd);

    bindExpand(writePipeline_);
    dispatchLinear(cmd, b.clusterCount, gpu::kExpandGroupSize);
    computeToComputeBarrier(cmd); // the next tile's scan reads the cursor this one advanced
}

void VegetationRenderer::draw(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame,
                              const DescriptorBinding& shadowMap, uint32_t slot, uint32_t lodMask) {
    if (pass == PlantPass::Main && mainShading_ == MainShading::Off) return;
    require(pass != PlantPass::TruthFlow || truthFlowPipeline_.handle, "VegetationRenderer::draw: enableFlow() first");
    if (pass == PlantPass::Main && mainShading_ == MainShading::Floor && !floorPipeline_.handle)
        floorPipeline_ = createGraphicsPipeline(ctx_.device, mainPipelineDesc("plant_floor.frag"), drawLayout(true));
    const Pipeline& pipeline = pass == PlantPass::Truth             ? truthPipeline_
                               : pass == PlantPass::TruthFlow       ? truthFlowPipeline_
                               : pass == PlantPass::Shadow          ? shadowPipeline_
                               : mainShading_ == MainShading::Floor ? floorPipeline_
                                                                    : mainPipeline_;
    vkCmdBindIndexBuffer(cmd, cornerIndices_.handle, 0, VK_INDEX_TYPE_UINT32);
    DescriptorBinding instances = storageBuffer(gpu::kBindingPlantInstances, instances_.handle);
    DescriptorBinding plants = storageBuffer(gpu::kBindingInstancePlants, instancePlants_.handle);
    const char* passName = pass == PlantPass::Main ? "main" : pass == PlantPass::Shadow ? "shadow" : "truth";
    static const char* const kLodNames[gpu::kLodCount] = {".near", ".mid", ".far"};
    const bool blades = scene_.lod.nearBlades > 0 && (lodMask & (1u << gpu::kLodNear)) &&
                        !(pass == PlantPass::Main && mainShading_ == MainShading::Floor);
    for (const auto& entry : tiles_) {
        // Not a structured binding: clang 14 (the sanitizer build) cannot capture one in the lambda below.
        const auto& tile = entry.second;
        if (!tile->expanded) continue;
        auto bind = [&](const Pipeline& p) {
            bindPipeline(cmd, p);
            if (pass == PlantPass::Main)
                pushDescriptors(ctx_.device, cmd, p,
                                {frame, constantsBinding(*tile, slot), instances, atlasCellsBinding(), atlasBinding(),
                                 shadowMap, plants});
            else if (pass == PlantPass::TruthFlow)
                pushDescriptors(
                    ctx_.device, cmd, p,
                    {frame, constantsBinding(*tile, slot), instances, atlasCellsBinding(), atlasBinding(), plants,
                     storageBuffer(gpu::kBindingFlowStatics, tile->buffers.statics.handle),
                     storageBuffer(gpu::kBindingFlowDynamicsPrevious, tile->keptStates[latestKept_ ^ 1u].handle),
                     storageBuffer(gpu::kBindingFlowDynamicsNext, tile->buffers.dynamics.handle)});
            else
                pushDescriptors(ctx_.device, cmd, p,
                                {frame, constantsBinding(*tile, slot), instances, atlasCellsBinding(), atlasBinding(),
                                 plants});
        };
        // The near blades first: opaque and nearest, they hide what the cards behind them would shade.
        if (blades) {
            bind(bladePipeline(pass));
            if (statistics_) statistics_->begin(cmd, std::string(passName) + ".blades");
            vkCmdDrawIndexedIndirect(cmd, tile->draws.handle, gpu::kLodCount * sizeof(VkDrawIndexedIndirectCommand), 1,
                                     sizeof(VkDrawIndexedIndirectCommand));
            if (statistics_) statistics_->end(cmd);
        }
        const Pipeline* bound = nullptr;
        for (uint32_t lod = 0; lod < gpu::kLodCount; ++lod) {
            if (!(lodMask & (1u << lod))) continue;
            // The main pass shades the far billboards with their own pipeline (plant.frag's FAR_BILLBOARDS).
            const Pipeline& p = &pipeline == &mainPipeline_ && lod == gpu::kLodFar ? mainFarPipeline_ : pipeline;
            if (bound != &p) bind(*(bound = &p));
            pushConstants(cmd, p, lod);
            if (statistics_) statistics_->begin(cmd, std::string(passName) + kLodNames[lod]);
            vkCmdDrawIndexedIndirect(cmd, tile->draws.handle, lod * sizeof(VkDrawIndexedIndirectCommand), 1,
                                     sizeof(VkDrawIndexedIndirectCommand));
            if (statistics_) statistics_->end(cmd);
        }
    }
}

GraphicsPipelineDesc truthFlowPipelineDesc(GraphicsPipelineDesc truth, VkFormat flowFormat) {
    auto flowName = [](const std::string& name) {
        const size_t dot = name.rfind('.');
        return name.substr(0, dot) + "_flow" + name.substr(dot);
    };
    truth.vertexShader = flowName(truth.vertexShader);
    truth.fragmentShader = flowName(truth.fragmentShader);
    truth.colorFormats.insert(truth.colorFormats.end(), {flowFormat, flowFormat}); // forward, backward
    return truth;
}

GraphicsPipelineDesc VegetationRenderer::truthPipelineDesc() const {
    GraphicsPipelineDesc truth = mainPipelineDesc("plant_truth.frag");
    truth.colorFormats = {formats_.truthDepthBits, formats_.truthLabel, formats_.truthNormal};
    truth.depthFormat = formats_.truthDepth;
    truth.samples = VK_SAMPLE_COUNT_1_BIT;
    truth.alphaToCoverage = false;
    truth.specialization = {/* PASS= */ gpu::kPassTruth, /* ALPHA_TO_COVERAGE= */ 0};
    return truth;
}

void VegetationRenderer::enableFlow() {
    if (truthFlowPipeline_.handle) return;
    PipelineLayoutDesc layout = drawLayout(false);
    for (uint32_t binding :
         {gpu::kBindingFlowStatics, gpu::kBindingFlowDynamicsPrevious, gpu::kBindingFlowDynamicsNext})
        layout.bindings.push_back(
            layoutBinding(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT));
    truthFlowPipeline_ =
        createGraphicsPipeline(ctx_.device, truthFlowPipelineDesc(truthPipelineDesc(), formats_.truthFlow), layout);
    for (auto& [key, tile] : tiles_) startKeptStates(*tile);
}

// Both kept states start as the live records, so neither is ever read uninitialised.
void VegetationRenderer::startKeptStates(Tile& tile) {
    const Buffer& live = tile.buffers.dynamics;
    const VkBufferCopy region{.size = live.size};
    for (Buffer& kept : tile.keptStates)
        kept = createBuffer(ctx_, live.size,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            MemoryIntent::DeviceLocal);
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        for (const Buffer& kept : tile.keptStates) vkCmdCopyBuffer(cmd, live.handle, kept.handle, 1, &region);
    });
}

void VegetationRenderer::recordKeepState(VkCommandBuffer cmd) {
    require(truthFlowPipeline_.handle, "VegetationRenderer::recordKeepState: enableFlow() first");
    latestKept_ ^= 1u;
    // The interaction tick's compute writes -> these copies; the copies' reads -> the next tick's writes (its barrier).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    for (const auto& [key, tile] : tiles_) { // every resident tile: any may be drawn, and later simulated
        const VkBufferCopy region{.size = tile->buffers.dynamics.size};
        vkCmdCopyBuffer(cmd, tile->buffers.dynamics.handle, tile->keptStates[latestKept_].handle, 1, &region);
    }
    // The copies -> the truth pass's vertex reads, and the live records' next writers (a tick's compute).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

std::vector<gpu::PlantDynamic> VegetationRenderer::readKeptState(std::optional<TileCoord> coord) {
    require(truthFlowPipeline_.handle, "VegetationRenderer::readKeptState: enableFlow() first");
    const Tile& tile = coord ? *tiles_.at(TileKey(coord->y, coord->x)) : onlyTile();
    std::vector<gpu::PlantDynamic> out(tile.buffers.plantCount);
    const std::vector<uint8_t> bytes = readBuffer(ctx_, tile.keptStates[latestKept_], 0, out.size() * sizeof(out[0]));
    if (!bytes.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

gpu::ExpansionStats VegetationRenderer::readStats() {
    gpu::ExpansionStats sum{};
    for (const auto& [key, tile] : tiles_) {
        if (!tile->expanded) continue;
        std::vector<uint8_t> bytes = readBuffer(ctx_, tile->stats, 0, sizeof(gpu::ExpansionStats));
        gpu::ExpansionStats stats;
        std::memcpy(&stats, bytes.data(), sizeof stats);
        sum.instances += stats.instances;
        sum.info += glm::uvec4(glm::uvec3(stats.info), 0u);
    }
    return sum;
}

} // namespace sward

namespace sward {

BakedPlants VegetationRenderer::bake(uint32_t slot) {
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    if (!bakePipeline_.handle)
        bakePipeline_ = createComputePipeline(
            ctx_.device, "plant_bake.comp",
            {.bindings = {layoutBinding(gpu::kBindingVegetation, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs),
                          layoutBinding(gpu::kBindingPlantInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs),
                          layoutBinding(gpu::kBindingAtlasCells, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs),
                          layoutBinding(gpu::kBindingBakedVertices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs)},
             .pushConstantSize = sizeof(gpu::BakeConstants),
             .pushConstantStages = cs});
    BakedPlants baked{.stats = readStats()};
    // [near | mid | far | near blades]: the blades (lod kLodCount in plant_bake.comp) of the near instances again.
    const uint32_t verticesPerPlant[gpu::kLodCount + 1] = {
        gpu::plantVertexCount(gpu::kLodNear, cutoutCorners_), gpu::plantVertexCount(gpu::kLodMid, cutoutCorners_),
        gpu::plantVertexCount(gpu::kLodFar, cutoutCorners_), scene_.lod.nearBlades * gpu::kBladeIndices};
    const uint32_t kept = std::min(baked.stats.instances.w, capacity_);
    auto keptOf = [&](uint32_t lod, uint32_t first) {
        const uint32_t l = lod == gpu::kLodCount ? gpu::kLodNear : lod;
        return std::min(baked.stats.instances[int(l)], kept - std::min(kept, first));
    };
    for (uint32_t lod = 0, first = 0; lod <= gpu::kLodCount; ++lod) {
        baked.vertexCount += keptOf(lod, lod == gpu::kLodCount ? 0u : first) * verticesPerPlant[lod];
        if (lod < gpu::kLodCount) first += baked.stats.instances[int(lod)];
    }
    baked.vertices = createBuffer(ctx_, std::max<uint64_t>(uint64_t(baked.vertexCount) * sizeof(gpu::BakedVertex), 16),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  MemoryIntent::DeviceLocal);
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        bindPipeline(cmd, bakePipeline_);
        pushDescriptors(ctx_.device, cmd, bakePipeline_,
                        {constantsBinding(onlyTile(), slot), storageBuffer(gpu::kBindingPlantInstances, instances_.handle),
                         atlasCellsBinding(), storageBuffer(gpu::kBindingBakedVertices, baked.vertices.handle)});
        for (uint32_t lod = 0, firstInstance = 0, firstVertex = 0; lod <= gpu::kLodCount; ++lod) {
            if (lod == gpu::kLodCount) firstInstance = 0; // the near instances' blades
            gpu::BakeConstants push{.lod = lod,
                                    .firstInstance = firstInstance,
                                    .firstVertex = firstVertex,
                                    .vertexCount = keptOf(lod, firstInstance) * verticesPerPlant[lod]};
            if (push.vertexCount > 0) {
                pushConstants(cmd, bakePipeline_, push);
                dispatchLinear(cmd, push.vertexCount, gpu::kComputeGroupSize);
            }
            if (lod < gpu::kLodCount) firstInstance += baked.stats.instances[int(lod)];
            firstVertex += push.vertexCount;
        }
        // Baked vertices are drawn (vertex shader) and read back by tests (copy).
        computeToVertexAndCopyBarrier(cmd);
    });
    return baked;
}

void VegetationRenderer::drawBaked(VkCommandBuffer cmd, const BakedPlants& baked, const DescriptorBinding& frame,
                                   const DescriptorBinding& shadowMap, uint32_t slot) {
    if (!staticPipeline_.handle) {
        std::vector<VkDescriptorSetLayoutBinding> bindings = plantDrawBindings();
        bindings.push_back(shadowMapLayoutBinding());
        const bool msaa = formats_.mainSamples != VK_SAMPLE_COUNT_1_BIT;
        staticPipeline_ = createGraphicsPipeline(
            ctx_.device,
            {.vertexShader = "plant_static.vert",
             .fragmentShader = "plant.frag",
             .cullMode = VK_CULL_MODE_NONE,
             .colorFormats = {formats_.mainColor},
             .depthFormat = formats_.mainDepth,
             .samples = formats_.mainSamples,
             .alphaToCoverage = msaa,
             .specialization = {/* PASS= */ gpu::kPassMain, /* ALPHA_TO_COVERAGE= */ msaa ? 1u : 0u}},
            {.bindings = bindings});
    }
    bindPipeline(cmd, staticPipeline_);
    pushDescriptors(ctx_.device, cmd, staticPipeline_,
                    {frame, constantsBinding(onlyTile(), slot), storageBuffer(gpu::kBindingPlantInstances, baked.vertices.handle),
                     atlasCellsBinding(), atlasBinding(), shadowMap});
    if (statistics_) statistics_->begin(cmd, "main.static");
    if (baked.vertexCount) vkCmdDraw(cmd, baked.vertexCount, 1, 0, 0);
    if (statistics_) statistics_->end(cmd);
}

void VegetationRenderer::destroyBaked(BakedPlants& baked) {
    retireBuffer(ctx_, baked.vertices);
    baked.vertexCount = 0;
}

} // namespace sward
