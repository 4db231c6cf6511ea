#include "render/track_renderer.h"

#include "engine/barriers.h"
#include "engine/resources.h"
#include "scene/world_tiles.h"

#include <algorithm>
#include <bit>

namespace sward {

namespace {

constexpr uint32_t kSide = gpu::kTrackPatchVertices; // vertices along a patch's side
constexpr uint32_t kPatchVertices = kSide * kSide;   // TerrainVertex per patch
// Vertices drawn per patch at level of detail `level` (every 2^level-th vertex): two triangles per cell, not indexed.
constexpr uint32_t patchDrawVertices(uint32_t level) {
    return ((kSide - 1) >> level) * ((kSide - 1) >> level) * 6;
}
static_assert(((kSide - 1) >> (gpu::kTrackLodLevels - 1)) << (gpu::kTrackLodLevels - 1) == kSide - 1,
              "every level of detail must tile the patch");
constexpr uint64_t kPatchBytes = uint64_t(kPatchVertices) * sizeof(gpu::TerrainVertex);
constexpr uint64_t kMaxUpdateBytes = 65536; // vkCmdUpdateBuffer's limit per call

// Writes `bytes` at `offset` of `buffer` from the command buffer, in calls of at most 64 KiB.
void updateBuffer(VkCommandBuffer cmd, const Buffer& buffer, uint64_t offset, std::span<const uint8_t> bytes) {
    for (uint64_t at = 0; at < bytes.size(); at += kMaxUpdateBytes)
        vkCmdUpdateBuffer(cmd, buffer.handle, offset + at, std::min<uint64_t>(kMaxUpdateBytes, bytes.size() - at),
                          bytes.data() + at);
}

// The main pass's patch grids, one per level of detail, back to back: each cell's two triangles as track.vert's
// truth path builds them (split along (i, j)-(i+1, j+1), the same corner order), indexing the grid's vertices row
// by row; `first` gets each level's first index, then the total.
std::vector<uint32_t> patchGridIndices(std::array<uint32_t, gpu::kTrackLodLevels + 1>& first) {
    std::vector<uint32_t> indices;
    for (uint32_t level = 0; level < gpu::kTrackLodLevels; ++level) {
        first[level] = uint32_t(indices.size());
        const uint32_t cells = (kSide - 1) >> level, side = cells + 1;
        for (uint32_t y = 0; y < cells; ++y)
            for (uint32_t x = 0; x < cells; ++x) {
                const uint32_t v00 = y * side + x, v10 = v00 + 1, v01 = v00 + side, v11 = v01 + 1;
                indices.insert(indices.end(), {v00, v10, v11, v00, v11, v01});
            }
    }
    first[gpu::kTrackLodLevels] = uint32_t(indices.size());
    return indices;
}

PipelineLayoutDesc with(PipelineLayoutDesc layout, VkDescriptorSetLayoutBinding binding) {
    layout.bindings.push_back(binding);
    return layout;
}

} // namespace

TrackRenderer::TrackRenderer(Context& ctx, const GraphicsPipelineDesc& main, const PipelineLayoutDesc& mainLayout,
                             const GraphicsPipelineDesc& truth, const PipelineLayoutDesc& truthLayout,
                             VkFormat flowFormat)
    : ctx_(ctx) {
    const VkDescriptorSetLayoutBinding table =
        layoutBinding(gpu::kBindingTrackTable, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT);
    const VkDescriptorSetLayoutBinding patch =
        layoutBinding(gpu::kBindingMeshVertices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT);
    const VkDescriptorSetLayoutBinding visible =
        layoutBinding(gpu::kBindingMeshIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT);
    GraphicsPipelineDesc desc = main;
    desc.fragmentShader = "terrain_holes.frag";
    holedMain_ = createGraphicsPipeline(ctx.device, desc, with(mainLayout, table));
    desc = truth;
    desc.fragmentShader = "truth_holes.frag";
    holedTruth_ = createGraphicsPipeline(ctx.device, desc, with(truthLayout, table));
    if (flowFormat != VK_FORMAT_UNDEFINED)
        holedTruthFlow_ =
            createGraphicsPipeline(ctx.device, truthFlowPipelineDesc(desc, flowFormat), with(truthLayout, table));
    // The patches pull their vertices (track.vert): indexed in the main pass (each grid vertex shaded once), three per
    // triangle in the truth pass (each vertex knows its triangle's normal).
    desc = main;
    desc.vertexShader = "track.vert";
    desc.vertexBindings = {};
    desc.vertexAttributes = {};
    desc.specialization = {/* PASS= */ gpu::kPassMain};
    patchMain_ = createGraphicsPipeline(ctx.device, desc, with(with(mainLayout, patch), visible));
    desc = truth;
    desc.vertexShader = "track.vert";
    desc.specialization = {/* PASS= */ gpu::kPassTruth};
    patchTruth_ = createGraphicsPipeline(ctx.device, desc, truthLayout); // its mesh indices: the patches drawn
    if (flowFormat != VK_FORMAT_UNDEFINED)
        patchTruthFlow_ = createGraphicsPipeline(ctx.device, truthFlowPipelineDesc(desc, flowFormat), truthLayout);
    const std::vector<uint32_t> indices = patchGridIndices(firstIndex_);
    gridIndices_ = createBufferWithData(ctx, bytesOf(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
}

TrackRenderer::~TrackRenderer() {
    destroyBuffer(ctx_, vertices_);
    destroyBuffer(ctx_, table_);
    destroyBuffer(ctx_, visible_);
    destroyBuffer(ctx_, gridIndices_);
    for (Pipeline* p : {&patchMain_, &patchTruth_, &holedMain_, &holedTruth_, &patchTruthFlow_, &holedTruthFlow_})
        destroyPipeline(ctx_.device, *p);
}

void TrackRenderer::setSource(const GroundTracks* tracks, const Ground* ground) {
    tracks_ = tracks;
    ground_ = ground;
    mesh_ = ground ? groundDrawMesh(*ground) : GroundDrawMesh{};
    world_ = nullptr;
    generation_ = ~uint64_t(0);
    seen_ = 0;
    slots_.clear();
    blockCount_ = 0;
}

void TrackRenderer::setWorldSource(const GroundTracks* tracks, const Scene& scene) {
    setSource(tracks, nullptr);
    world_ = &scene;
}

std::vector<gpu::TerrainVertex> trackPatchVertices(const GroundTracks& tracks, const Ground& ground,
                                                   const GroundDrawMesh& mesh, TrackBlockKey key) {
    std::vector<gpu::TerrainVertex> patch(kPatchVertices);
    const int64_t i0 = int64_t(key.x) * gpu::kTrackBlockCells - gpu::kTrackPatchRing;
    const int64_t j0 = int64_t(key.y) * gpu::kTrackBlockCells - gpu::kTrackPatchRing;
    for (uint32_t v = 0; v < kSide; ++v)
        for (uint32_t u = 0; u < kSide; ++u) {
            const int64_t i = i0 + u, j = j0 + v;
            gpu::TerrainVertex vertex = groundVertexAt(ground, mesh, trackVertexPosition(i, j));
            const float rut = tracks.depth(i, j);
            const glm::vec2 slope((tracks.depth(i + 1, j) - tracks.depth(i - 1, j)) / (2.0f * gpu::kTrackCell),
                                  (tracks.depth(i, j + 1) - tracks.depth(i, j - 1)) / (2.0f * gpu::kTrackCell));
            // The ground h has normal ~ (-dh/dx, -dh/dy, 1); the pressed ground h - rut adds (drut/dx, drut/dy, 0).
            const glm::vec3 n = glm::vec3(vertex.normal) / vertex.normal.z + glm::vec3(slope, 0.0f);
            vertex.normal = glm::vec4(glm::normalize(n), 0.0f);
            vertex.positionHeight.z -= rut;
            vertex.positionHeight.w = rut;
            patch[size_t(v) * kSide + u] = vertex;
        }
    return patch;
}

std::vector<gpu::TerrainVertex> worldTrackPatchVertices(const GroundTracks& tracks, const Scene& scene,
                                                        TrackBlockKey key) {
    const int64_t i0 = int64_t(key.x) * gpu::kTrackBlockCells - gpu::kTrackPatchRing;
    const int64_t j0 = int64_t(key.y) * gpu::kTrackBlockCells - gpu::kTrackPatchRing;
    const Ground ground = latticeGround(scene, glm::dvec2(trackVertexPosition(i0, j0)),
                                        glm::dvec2(trackVertexPosition(i0 + kSide - 1, j0 + kSide - 1)), 0.0);
    return trackPatchVertices(tracks, ground, groundDrawMesh(ground), key);
}

void TrackRenderer::uploadBlock(VkCommandBuffer cmd, uint32_t slot, TrackBlockKey key) {
    const std::vector<gpu::TerrainVertex> patch =
        world_ ? worldTrackPatchVertices(*tracks_, *world_, key) : trackPatchVertices(*tracks_, *ground_, mesh_, key);
    glm::vec2 heights(INFINITY, -INFINITY);
    for (const gpu::TerrainVertex& vertex : patch)
        heights = glm::vec2(std::min(heights.x, vertex.positionHeight.z), std::max(heights.y, vertex.positionHeight.z));
    heights_[slot] = heights;
    updateBuffer(cmd, vertices_, slot * kPatchBytes,
                 std::span(reinterpret_cast<const uint8_t*>(patch.data()), kPatchBytes));
}

// The open-addressing table of patched blocks (ground_tracks.glsl): a power of two of at least twice the blocks,
// linear probing from gpu::trackBlockHash, entries (x, y, instance, 0), empty slots kTrackEmptyKey.
void TrackRenderer::uploadTable(VkCommandBuffer cmd) {
    const uint32_t size = std::max(64u, std::bit_ceil(2 * blockCount_));
    std::vector<glm::ivec4> entries(size, glm::ivec4(gpu::kTrackEmptyKey, gpu::kTrackEmptyKey, 0, 0));
    for (const auto& [key, slot] : slots_) {
        uint32_t at = gpu::trackBlockHash(key.x, key.y) & (size - 1);
        while (entries[at].x != gpu::kTrackEmptyKey) at = (at + 1) & (size - 1);
        entries[at] = glm::ivec4(key.x, key.y, int32_t(slot), 0);
    }
    const uint64_t bytes = entries.size() * sizeof(glm::ivec4);
    if (table_.size != bytes) {
        retireBuffer(ctx_, table_);
        table_ = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              MemoryIntent::DeviceLocal);
    }
    updateBuffer(cmd, table_, 0, bytesOf(entries));
}

// Room for `blocks` patches; a larger buffer starts empty (every block is uploaded again).
void TrackRenderer::reserve(uint32_t blocks) {
    if (blocks <= capacity_) return;
    capacity_ = std::max(16u, std::bit_ceil(blocks));
    retireBuffer(ctx_, vertices_);
    vertices_ =
        createBuffer(ctx_, capacity_ * kPatchBytes,
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::DeviceLocal);
    heights_.resize(capacity_);
    seen_ = 0;
}

void TrackRenderer::update(VkCommandBuffer cmd, const Camera& reference, const std::array<glm::vec4, 5>& planes,
                           uint32_t dataSlot, std::span<const TrackTileRect> tiles) {
    upload(cmd);
    if (active()) cull(reference, planes, dataSlot, tiles);
}

void TrackRenderer::upload(VkCommandBuffer cmd) {
    if (!tracks_ || tracks_->revision() == seen_) return; // idle ground: nothing to do
    if (tracks_->generation() != generation_) {           // a restored state: start afresh
        generation_ = tracks_->generation();
        slots_.clear();
        seen_ = 0;
    }
    const TrackBlocks& blocks = tracks_->blocks();
    const bool grown = blocks.size() != slots_.size();
    reserve(uint32_t(blocks.size()));
    // Earlier frames may still read the buffers: their draws complete before these writes.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT);
    for (const auto& entry : blocks) {
        const auto [it, added] = slots_.try_emplace(entry.first, uint32_t(slots_.size()));
        if (added || tracks_->blockRevision(entry.first) > seen_) uploadBlock(cmd, it->second, entry.first);
    }
    blockCount_ = uint32_t(slots_.size());
    if (grown || seen_ == 0) uploadTable(cmd);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    seen_ = tracks_->revision();
}

// The patches whose box (the block, its ring, its lowest and highest vertex) reaches into the frustum, per drawn tile
// those overlapping it, in block order within each level of detail: level 0 where a lattice cell spans at least a
// pixel at the box's nearest point to the reference camera, level 1 (every 2nd vertex) down to half a pixel, level 2
// (every 4th) beyond.
void TrackRenderer::cull(const Camera& reference, const std::array<glm::vec4, 5>& planes, uint32_t dataSlot,
                         std::span<const TrackTileRect> tiles) {
    constexpr float kBlockMetres = gpu::kTrackCell * float(gpu::kTrackBlockCells);
    constexpr float kRingMetres = gpu::kTrackCell * float(gpu::kTrackPatchRing);
    const double level0Distance = reference.fy * gpu::kTrackCell; // a cell is one pixel there
    std::vector<std::array<std::vector<uint32_t>, gpu::kTrackLodLevels>> levels(tiles.size());
    uint32_t entries = 0;
    for (const auto& [key, slot] : slots_) {
        const glm::vec3 lo(float(key.x) * kBlockMetres - kRingMetres, float(key.y) * kBlockMetres - kRingMetres,
                           heights_[slot].x);
        const glm::vec3 hi(lo.x + kBlockMetres + 2.0f * kRingMetres, lo.y + kBlockMetres + 2.0f * kRingMetres,
                           heights_[slot].y);
        bool inside = true;
        for (const glm::vec4& plane : planes) { // the box corner furthest along the plane's normal
            const glm::vec3 far(plane.x >= 0.0f ? hi.x : lo.x, plane.y >= 0.0f ? hi.y : lo.y,
                                plane.z >= 0.0f ? hi.z : lo.z);
            inside = inside && glm::dot(glm::vec3(plane), far) + plane.w >= 0.0f;
        }
        if (!inside) continue;
        const double distance =
            glm::distance(reference.position, glm::clamp(reference.position, glm::dvec3(lo), glm::dvec3(hi)));
        const uint32_t level = distance < level0Distance ? 0 : distance < 2.0 * level0Distance ? 1 : 2;
        for (size_t t = 0; t < tiles.size(); ++t)
            if (double(hi.x) >= tiles[t].min.x && double(lo.x) <= tiles[t].max.x && double(hi.y) >= tiles[t].min.y &&
                double(lo.y) <= tiles[t].max.y)
                levels[t][level].push_back(slot | level << gpu::kTrackLodShift), ++entries;
    }
    // Room for every entry; frames still in flight keep reading the buffer they were recorded with.
    if (entries > visibleCapacity_ || !visible_) {
        visibleCapacity_ = std::max({16u, capacity_, std::bit_ceil(entries)});
        retireBuffer(ctx_, visible_);
        visible_ = createBuffer(ctx_, uint64_t(visibleCapacity_) * sizeof(uint32_t) * gpu::kFrameDataSlots,
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryIntent::Upload);
    }
    uint32_t* visible = reinterpret_cast<uint32_t*>(visible_.mapped()) + size_t(dataSlot) * visibleCapacity_;
    visibleCount_ = 0;
    firstVisible_.assign(tiles.size(), {});
    for (size_t t = 0; t < tiles.size(); ++t) {
        for (uint32_t level = 0; level < gpu::kTrackLodLevels; ++level) {
            firstVisible_[t][level] = visibleCount_;
            std::copy(levels[t][level].begin(), levels[t][level].end(), visible + visibleCount_);
            visibleCount_ += uint32_t(levels[t][level].size());
        }
        firstVisible_[t][gpu::kTrackLodLevels] = visibleCount_;
    }
    dataSlot_ = dataSlot;
}

void TrackRenderer::drawVisible(VkCommandBuffer cmd, bool indexed, uint32_t tileIndex) const {
    const std::array<uint32_t, gpu::kTrackLodLevels + 1>& first = firstVisible_[tileIndex];
    for (uint32_t level = 0; level < gpu::kTrackLodLevels; ++level) {
        const uint32_t instances = first[level + 1] - first[level];
        if (instances == 0) continue;
        if (indexed)
            vkCmdDrawIndexed(cmd, firstIndex_[level + 1] - firstIndex_[level], instances, firstIndex_[level], 0,
                             first[level]);
        else
            vkCmdDraw(cmd, patchDrawVertices(level), instances, 0, first[level]);
    }
}

DescriptorBinding TrackRenderer::visibleBinding() const {
    const uint64_t bytes = uint64_t(visibleCapacity_) * sizeof(uint32_t);
    return storageBuffer(gpu::kBindingMeshIndices, visible_.handle, dataSlot_ * bytes, bytes);
}

DescriptorBinding TrackRenderer::tableBinding() const {
    return storageBuffer(gpu::kBindingTrackTable, table_.handle);
}

void TrackRenderer::drawMain(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& shadow,
                             const DescriptorBinding& cover, const DescriptorBinding& textures,
                             const DescriptorBinding& groundMaterials, const gpu::TerrainTileConstants& tile,
                             uint32_t tileIndex) {
    if (tileIndex >= firstVisible_.size() || firstVisible_[tileIndex][0] == firstVisible_[tileIndex].back()) return;
    bindPipeline(cmd, patchMain_);
    pushDescriptors(ctx_.device, cmd, patchMain_,
                    {frame, shadow, cover, textures, groundMaterials,
                     storageBuffer(gpu::kBindingMeshVertices, vertices_.handle), visibleBinding()});
    pushConstants(cmd, patchMain_, tile);
    vkCmdBindIndexBuffer(cmd, gridIndices_.handle, 0, VK_INDEX_TYPE_UINT32);
    drawVisible(cmd, true, tileIndex);
}

void TrackRenderer::drawTruth(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& cover,
                              const gpu::TerrainTileConstants& tile, bool flow, uint32_t tileIndex) {
    if (tileIndex >= firstVisible_.size() || firstVisible_[tileIndex][0] == firstVisible_[tileIndex].back()) return;
    const Pipeline& pipeline = flow ? patchTruthFlow_ : patchTruth_;
    bindPipeline(cmd, pipeline);
    pushDescriptors(ctx_.device, cmd, pipeline,
                    {frame, storageBuffer(gpu::kBindingMeshVertices, vertices_.handle), visibleBinding(), cover});
    pushConstants(cmd, pipeline, tile);
    drawVisible(cmd, false, tileIndex);
}

} // namespace sward
