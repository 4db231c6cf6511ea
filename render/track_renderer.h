// TrackRenderer: draws the ruts of GroundTracks (interaction/ground_tracks.h) as real geometry, in colour and in
// ground truth, exactly where they were pressed.
//
// Every track block holding a rut is drawn as a fine patch of the ground (track.vert): a grid of
// gpu::kTrackPatchVertices^2 vertices at the ground's height minus the rut, with the coarse ground's normal (tilted
// by the rut's slope), colour and texture coordinate at each vertex, so where the ground is unpressed the patch is
// the ground. The coarse ground is then drawn with holes: its fragments inside a patched block are discarded
// (ground_tracks.glsl looks the block up in an open-addressing table). Patches reach two lattice cells into their
// neighbours, so no crack opens along a block's edge. Without any rut nothing here is drawn or looked up: the ground
// keeps its plain pipelines and idle ground costs nothing.
//
// update() records the upload of the blocks changed since the last frame (vkCmdUpdateBuffer into the frame's command
// buffer: only the touched blocks' vertices, ordered after the frames before it) and culls the patches against the
// frame's frustum: a draw's instances are the patches in view, in block order, one draw per level of detail (every
// vertex, every 2nd, every 4th: a cell about a pixel wide). Both views of a stereo pair and the truth pass draw the
// same levels, chosen from the reference camera, so the truth is always the drawn geometry. The sun shadow pass draws
// the coarse ground without holes: a rut lies at most its depth below it, within the shadow bias of 5 cm or more
// (world/sun_shadow.h), so ruts up to that depth are lit as the ground around them.

#pragma once

#include "engine/context.h"
#include "engine/pipelines.h"
#include "interaction/ground_tracks.h"
#include "render/ground_mesh.h"
#include "render/vegetation_renderer.h" // PlantPass
#include "scene/scene.h"
#include "world/camera.h"

#include <array>
#include <cmath>
#include <map>
#include <span>
#include <vector>

namespace sward {

// The gpu::kTrackPatchVertices^2 vertices of block `key`'s patch, row by row: lattice vertices [-ring, kTrackBlockCells
// + ring] around the block's first, each the coarse ground's vertex there (groundVertexAt on `mesh` =
// groundDrawMesh(ground)) pressed down by the rut (positionHeight.w: the rut's depth), its normal tilted by the rut's
// slope. What TrackRenderer draws, and what the range sensors see (render_job).
std::vector<gpu::TerrainVertex> trackPatchVertices(const GroundTracks& tracks, const Ground& ground,
                                                   const GroundDrawMesh& mesh, TrackBlockKey key);

// trackPatchVertices in a world (scene.world): the unpressed ground is the world's lattice ground around the block
// (latticeGround: the tiles' heights bitwise), so a patch is the same whichever tiles are resident.
std::vector<gpu::TerrainVertex> worldTrackPatchVertices(const GroundTracks& tracks, const Scene& scene,
                                                        TrackBlockKey key);

// A drawn tile's xy square (SceneRenderer's tiles within the view distance): a world draws each patch with every tile
// it overlaps, with that tile's cover and constants.
struct TrackTileRect {
    glm::dvec2 min{-INFINITY}, max{INFINITY};
};

class TrackRenderer {
public:
    // `main` / `truth`: the terrain's main and truth pipelines (terrain.vert + terrain.frag, terrain_truth.vert +
    // truth.frag) with their layouts; the patches and the holed ground are drawn with the same state. `flowFormat`
    // (not VK_FORMAT_UNDEFINED): also the truth pass with flow (PlantPass::TruthFlow), with this attachment format.
    TrackRenderer(Context& ctx, const GraphicsPipelineDesc& main, const PipelineLayoutDesc& mainLayout,
                  const GraphicsPipelineDesc& truth, const PipelineLayoutDesc& truthLayout,
                  VkFormat flowFormat = VK_FORMAT_UNDEFINED);
    ~TrackRenderer();
    TrackRenderer(const TrackRenderer&) = delete;
    TrackRenderer& operator=(const TrackRenderer&) = delete;

    // The ruts to draw and the ground they are pressed into; both must outlive the renderer.
    void setSource(const GroundTracks* tracks, const Ground* ground);
    // The ruts of a world (worldTrackPatchVertices); `tracks` and `scene` must outlive the renderer.
    void setWorldSource(const GroundTracks* tracks, const Scene& scene);
    // Records the upload of every block changed since the last call and picks the patches inside the frame's
    // frustum `planes` (world space, inward, as Camera::frustumPlanes), each at the level of detail its distance to
    // the `reference` camera asks for, for the draws of data slot `dataSlot` (< gpu::kFrameDataSlots, not in use by
    // a frame still executing). Outside any rendering pass.
    // `tiles`: the tiles drawn this frame, in drawing order; drawMain / drawTruth of tile k draw
    // the patches overlapping tiles[k]. A one-tile scene: one unbounded rect.
    void update(VkCommandBuffer cmd, const Camera& reference, const std::array<glm::vec4, 5>& planes, uint32_t dataSlot,
                std::span<const TrackTileRect> tiles = kOneTile);
    static constexpr TrackTileRect kOneTile[1] = {TrackTileRect{}};

    bool active() const { return blockCount_ > 0; } // some rut is drawn
    // The coarse ground's pipeline for the main or truth pass, with holes where patches lie (active() only), and
    // the table binding it needs beside the terrain's own.
    const Pipeline& holedGround(PlantPass pass) const {
        return pass == PlantPass::Main ? holedMain_ : pass == PlantPass::TruthFlow ? holedTruthFlow_ : holedTruth_;
    }
    DescriptorBinding tableBinding() const;
    // Draw every patch into the current main / truth pass, with the terrain's bindings for that pass (less its mesh
    // buffers) and the tile's push constants.
    void drawMain(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& shadow,
                  const DescriptorBinding& cover, const DescriptorBinding& textures,
                  const DescriptorBinding& groundMaterials, const gpu::TerrainTileConstants& tile,
                  uint32_t tileIndex = 0);
    void drawTruth(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& cover,
                   const gpu::TerrainTileConstants& tile, bool flow = false, uint32_t tileIndex = 0);

private:
    void upload(VkCommandBuffer cmd);
    void uploadBlock(VkCommandBuffer cmd, uint32_t slot, TrackBlockKey key);
    void uploadTable(VkCommandBuffer cmd);
    void reserve(uint32_t blocks);
    void cull(const Camera& reference, const std::array<glm::vec4, 5>& planes, uint32_t dataSlot,
              std::span<const TrackTileRect> tiles);
    void drawVisible(VkCommandBuffer cmd, bool indexed, uint32_t tileIndex) const;
    DescriptorBinding visibleBinding() const;

    Context& ctx_;
    const GroundTracks* tracks_ = nullptr;
    const Ground* ground_ = nullptr;
    const Scene* world_ = nullptr;                  // a world's scene: patches on its lattice ground
    GroundDrawMesh mesh_;                           // the coarse ground's attributes, interpolated at patch vertices
    uint64_t generation_ = ~uint64_t(0), seen_ = 0; // of the tracks last uploaded
    std::map<TrackBlockKey, uint32_t> slots_;       // block -> its patch's slot in vertices_
    std::vector<glm::vec2> heights_;                // per slot: the patch's lowest and highest vertex z
    uint32_t blockCount_ = 0, capacity_ = 0, visibleCount_ = 0, dataSlot_ = 0;
    // Per drawn tile, each level's first entry, then the tile's end (the next tile's first).
    std::vector<std::array<uint32_t, gpu::kTrackLodLevels + 1>> firstVisible_;
    Buffer vertices_, table_;
    Buffer visible_; // per data slot, visibleCapacity_ uints: the slots of the patches drawn (host-visible)
    uint32_t visibleCapacity_ = 0;
    Buffer gridIndices_; // the main pass's grid triangles per level of detail (patchGridIndices)
    std::array<uint32_t, gpu::kTrackLodLevels + 1> firstIndex_{};
    Pipeline patchMain_, patchTruth_, holedMain_, holedTruth_, patchTruthFlow_, holedTruthFlow_;
};

} // namespace sward
