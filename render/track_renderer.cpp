#include "render/track_renderer.h"

#include "engine/barriers.h"
#include "engine/resources.h"

#include <algorithm>
#include <bit>

namespace sward {

namespace {

constexpr uint32_t kSide = gpu::kTrackPatchVertices;              // vertices along a patch's side
constexpr uint32_t kPatchVertices = kSide * kSide;               // TerrainVertex per patch
constexpr uint32_t kPatchDrawVertices = (kSide - 1) * (kSide - 1) * 6; // two triangles per cell, not indexed
constexpr uint64_t kPatchBytes = uint64_t(kPatchVertices) * sizeof(gpu::TerrainVertex);
constexpr uint64_t kMaxUpdateBytes = 65536; // vkCmdUpdateBuffer's limit per call

// Writes `bytes` at `offset` of `buffer` from the command buffer, in calls of at most 64 KiB.
void updateBuffer(VkCommandBuffer cmd, const Buffer& buffer, uint64_t offset, std::span<const uint8_t> bytes) {
    for (uint64_t at = 0; at < bytes.size(); at += kMaxUpdateBytes)
        vkCmdUpdateBuffer(cmd, buffer.handle, offset + at, std::min<uint64_t>(kMaxUpdateBytes, bytes.size() - at),
                          bytes.data() + at);
}

// A pipeline layout without one of its bindings.
PipelineLayoutDesc without(PipelineLayoutDesc layout, uint32_t binding) {
    std::erase_if(layout.bindings, [&](const VkDescriptorSetLayoutBinding& b) { return b.binding == binding; });
    return layout;
}

PipelineLayoutDesc with(PipelineLayoutDesc layout, VkDescriptorSetLayoutBinding binding) {
    layout.bindings.push_back(binding);
    return layout;
}

} // namespace

TrackRenderer::TrackRenderer(Context& ctx, const GraphicsPipelineDesc& main, const PipelineLayoutDesc& mainLayout,
                             const GraphicsPipelineDesc& truth, const PipelineLayoutDesc& truthLayout)
    : ctx_(ctx) {
    const VkDescriptorSetLayoutBinding table =
        layoutBinding(gpu::kBindingTrackTable, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT);
    const VkDescriptorSetLayoutBinding patch =
        layoutBinding(gpu::kBindingMeshVertices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT);
    GraphicsPipelineDesc desc = main;
    desc.fragmentShader = "terrain_holes.frag";
    holedMain_ = createGraphicsPipeline(ctx.device, desc, with(mainLayout, table));
    desc = truth;
    desc.fragmentShader = "truth_holes.frag";
    holedTruth_ = createGraphicsPipeline(ctx.device, desc, with(truthLayout, table));
    // The patches pull their vertices (track.vert), so each also knows its triangle's normal for the truth pass.
    desc = main;
    desc.vertexShader = "track.vert";
    desc.vertexBindings = {};
    desc.vertexAttributes = {};
    desc.specialization = {/* PASS= */ gpu::kPassMain};
    patchMain_ = createGraphicsPipeline(ctx.device, desc, with(mainLayout, patch));
    desc = truth;
    desc.vertexShader = "track.vert";
    desc.specialization = {/* PASS= */ gpu::kPassTruth};
    patchTruth_ = createGraphicsPipeline(ctx.device, desc, without(truthLayout, gpu::kBindingMeshIndices));
}

TrackRenderer::~TrackRenderer() {
    destroyBuffer(ctx_, vertices_);
    destroyBuffer(ctx_, table_);
    for (Pipeline* p : {&patchMain_, &patchTruth_, &holedMain_, &holedTruth_}) destroyPipeline(ctx_.device, *p);
}

void TrackRenderer::setSource(const GroundTracks* tracks, const Ground* ground) {
    tracks_ = tracks;
    ground_ = ground;
    mesh_ = ground ? groundDrawMesh(*ground) : GroundDrawMesh{};
    generation_ = ~uint64_t(0);
    seen_ = 0;
    slots_.clear();
    blockCount_ = 0;
}

// The patch of block `key`: lattice vertices [-1, kTrackBlockCells + 2) around the block's first, each the coarse
// ground's vertex there pressed down by the rut, its normal tilted by the rut's slope (central differences).
void TrackRenderer::uploadBlock(VkCommandBuffer cmd, uint32_t slot, TrackBlockKey key) {
    std::vector<gpu::TerrainVertex> patch(kPatchVertices);
    const int64_t i0 = int64_t(key.x) * gpu::kTrackBlockCells - 1, j0 = int64_t(key.y) * gpu::kTrackBlockCells - 1;
    for (uint32_t v = 0; v < kSide; ++v)
        for (uint32_t u = 0; u < kSide; ++u) {
            const int64_t i = i0 + u, j = j0 + v;
            gpu::TerrainVertex vertex = groundVertexAt(*ground_, mesh_, trackVertexPosition(i, j));
            const float rut = tracks_->depth(i, j);
            const glm::vec2 slope((tracks_->depth(i + 1, j) - tracks_->depth(i - 1, j)) / (2.0f * gpu::kTrackCell),
                                  (tracks_->depth(i, j + 1) - tracks_->depth(i, j - 1)) / (2.0f * gpu::kTrackCell));
            // The ground h has normal ~ (-dh/dx, -dh/dy, 1); the pressed ground h - rut adds (drut/dx, drut/dy, 0).
            const glm::vec3 n = glm::vec3(vertex.normal) / vertex.normal.z + glm::vec3(slope, 0.0f);
            vertex.normal = glm::vec4(glm::normalize(n), 0.0f);
            vertex.positionHeight.z -= rut;
            vertex.positionHeight.w = rut;
            patch[size_t(v) * kSide + u] = vertex;
        }
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
    updateBuffer(cmd, table_, 0, std::span(reinterpret_cast<const uint8_t*>(entries.data()), bytes));
}

// Room for `blocks` patches; a larger buffer starts empty (every block is uploaded again).
void TrackRenderer::reserve(uint32_t blocks) {
    if (blocks <= capacity_) return;
    capacity_ = std::max(16u, std::bit_ceil(blocks));
    retireBuffer(ctx_, vertices_);
    vertices_ = createBuffer(ctx_, capacity_ * kPatchBytes,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             MemoryIntent::DeviceLocal);
    seen_ = 0;
}

void TrackRenderer::update(VkCommandBuffer cmd) {
    if (!tracks_ || tracks_->revision() == seen_) return; // idle ground: nothing to do
    if (tracks_->generation() != generation_) { // a restored state: start afresh
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

DescriptorBinding TrackRenderer::tableBinding() const { return storageBuffer(gpu::kBindingTrackTable, table_.handle); }

void TrackRenderer::drawMain(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& shadow,
                             const DescriptorBinding& cover, const DescriptorBinding& textures,
                             const gpu::TerrainTileConstants& tile) {
    if (!active()) return;
    bindPipeline(cmd, patchMain_);
    pushDescriptors(ctx_.device, cmd, patchMain_,
                    {frame, shadow, cover, textures, storageBuffer(gpu::kBindingMeshVertices, vertices_.handle)});
    pushConstants(cmd, patchMain_, tile);
    vkCmdDraw(cmd, kPatchDrawVertices, blockCount_, 0, 0);
}

void TrackRenderer::drawTruth(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& cover,
                              const gpu::TerrainTileConstants& tile) {
    if (!active()) return;
    bindPipeline(cmd, patchTruth_);
    pushDescriptors(ctx_.device, cmd, patchTruth_,
                    {frame, storageBuffer(gpu::kBindingMeshVertices, vertices_.handle), cover});
    pushConstants(cmd, patchTruth_, tile);
    vkCmdDraw(cmd, kPatchDrawVertices, blockCount_, 0, 0);
}

} // namespace sward
