// VegetationRenderer: per-frame compute expansion of point plants into LOD instances and their draws.
//
// Frame flow (docs/architecture.md), per resident tile in (y, x) order:
//   expand()  count pass (workgroup per cluster: frustum + distance cull, LOD choice, per-LOD counts)
//             -> scan (one workgroup: exclusive prefix sums in cluster order -> offsets + 3 indirect draws)
//             -> write pass (same choices; instances written at offset + rank: a fixed, deterministic order)
//   draw()    three vkCmdDrawIndirect (near 4 quads, mid 2 quads, far 1 billboard) into the current pass, and with
//             lod.near_blades a fourth before them: the near plants of the grass categories as opaque blades
//             (shaders/plant_blade.vert, vegetation_blades.cpp), whose near cards the first leaves out;
//             main colour (alpha-to-coverage at 4x MSAA, alpha test at 1x), ground truth or sun shadow map;
//             with setCutout(N), near and mid quads as fans over their atlas cell's cut-out polygon.
// The tiles share one instance pool: each scan starts where the previous tile's ended (a GPU-side cursor), so the
// pool is sized by what a frame shows, not by the number of resident tiles. A tile whose clusters are all culled
// adds nothing, so a frame is the same whether tiles out of sight are resident or not.
#pragma once

#include "vegetation/atlas.h"
#include "world/camera.h"
#include "engine/context.h"
#include "engine/pipeline_statistics.h"
#include "engine/pipelines.h"
#include "scene/scene.h"
#include "render/vegetation_buffers.h"

#include "shared/config.h"
#include "shared/gpu_layout.h"

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <utility>

namespace sward {

// TruthFlow: the truth pass with motion ground truth (render.flow): two more attachments, each pixel's flow to the next
// and the previous tick (shaders/shared/flow_fragment.glsl).
enum class PlantPass { Main, Truth, Shadow, TruthFlow };

// The latest expansion baked into static vertices ([near | mid | far | near blades]), for baselines and reference
// tests.
struct BakedPlants {
    Buffer vertices;          // gpu::BakedVertex[vertexCount]
    uint32_t vertexCount = 0;
    gpu::ExpansionStats stats{};
};

struct VegetationPassFormats {
    VkFormat mainColor, mainDepth;
    VkSampleCountFlagBits mainSamples;
    VkFormat truthDepthBits, truthLabel, truthNormal, truthDepth; // truth attachments: depth bits, label, normal
    VkFormat truthFlow; // the two flow attachments of the truth pass with flow (PlantPass::TruthFlow)
    VkFormat shadowDepth;
};

// The truth pipeline `truth` with motion ground truth: its shaders built with SWARD_FLOW ("<name>_flow.<stage>",
// shaders/CMakeLists.txt) and the two flow attachments after its three.
GraphicsPipelineDesc truthFlowPipelineDesc(GraphicsPipelineDesc truth, VkFormat flowFormat);

class VegetationRenderer {
public:
    // Uploads the atlas (with its mip chain) and builds the pipelines; plants come with addTile(). The frame's
    // instance pool holds `instanceCapacity` instances (instanceCapacityFor).
    VegetationRenderer(Context& ctx, const Scene& scene, const Atlas& atlas, const VegetationPassFormats& formats,
                       uint32_t instanceCapacity);
    // A pool for `plants` plants: each yields at most two instances (inside a cross-fade band); at most 4 M.
    static uint32_t instanceCapacityFor(uint64_t plants);

    // Uploads a tile's records (one submission; waits). Requires a tile with fields, not resident yet.
    void addTile(const VegetationTile& tile);
    // Drops a resident tile; its buffers are destroyed once the frames in flight are done with them.
    void removeTile(TileCoord coord);
    // The wind from the next expand on (a program's change between frames, render/session.h).
    void setWind(const WindParams& wind) { scene_.wind = wind; }
    bool hasTile(TileCoord coord) const;
    uint32_t tileCount() const { return uint32_t(tiles_.size()); }
    ~VegetationRenderer();
    VegetationRenderer(const VegetationRenderer&) = delete;
    VegetationRenderer& operator=(const VegetationRenderer&) = delete;

    // Records the three expansion dispatches for this camera and simulation time. `slot` selects the
    // constants slot (taken modulo gpu::kFrameDataSlots).
    // `cullPlanes` (optional) replaces the camera's frustum for culling, e.g. the union of a stereo pair's.
    void expand(VkCommandBuffer cmd, const Camera& camera, double timeSeconds, uint32_t slot,
                const std::array<glm::vec4, 5>* cullPlanes = nullptr);
    // Records the plant draws into the current rendering pass. `frame` is the frame-constants binding;
    // `shadowMap` is the sampled sun shadow map for the main pass (ignored otherwise). `lodMask`: bit l draws LOD l
    // (the shadow pass leaves out the LODs that cannot reach a cascade).
    void draw(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame, const DescriptorBinding& shadowMap,
              uint32_t slot, uint32_t lodMask = (1u << gpu::kLodCount) - 1u);

    // Motion ground truth (render.flow): the truth pass with flow places each plant's points with its state at the
    // previous tick and at the next. enableFlow() makes the pipeline and, for every resident tile, two buffers for kept
    // states; recordKeepState() copies every resident tile's live dynamic records into one of them, alternately. A draw
    // with TruthFlow reads the state kept before the latest keep as the previous tick's and the live records as the
    // next tick's: so keep the state of tick t - 1, render tick t, keep tick t's state and run tick t + 1, then draw
    // the truth. Both kept states start as the live records, at enableFlow() and for a tile added after it (a world's
    // tile made resident: no tick changed it while it was not), so plants no simulation moves need no keep at all.
    void enableFlow();
    void recordKeepState(VkCommandBuffer cmd);
    // The dynamic records recordKeepState() copied last from resident tile `coord` (none: the only tile; reads back,
    // waits): after a frame with flow, the plants' state of the frame's own tick, which its cameras drew, while the
    // live records already hold the next tick's (the range sensors' sweep of that frame, render/sequence_frame.h).
    // Requires enableFlow().
    std::vector<gpu::PlantDynamic> readKeptState(std::optional<TileCoord> coord = {});

    // Statistics of the latest expansion, summed over the tiles (reads back; waits for the GPU). info.w: 0.
    gpu::ExpansionStats readStats();
    // Bakes the latest expansion's quads into static vertices (one submission; waits). One tile only.
    BakedPlants bake(uint32_t slot);
    // Draws baked vertices into the current main pass, with the main pass's fragment shading.
    void drawBaked(VkCommandBuffer cmd, const BakedPlants& baked, const DescriptorBinding& frame,
                   const DescriptorBinding& shadowMap, uint32_t slot);
    void destroyBaked(BakedPlants& baked);
    // Cut-out quads (vegetation/atlas_cutout.h): with `corners` 4..8, near and mid quads are drawn as their atlas
    // cell's cut-out polygon of that many corners, so their transparent margins are not rasterised; 0: whole quads
    // (the default: see docs/benchmarks.md, "Fragment work", for why). Used by the next expand() and its bake().
    // `atlas` is the one the renderer was made with: its polygons are fitted on the first use of a corner count.
    void setCutout(uint32_t corners, const Atlas& atlas);
    uint32_t cutoutCorners() const { return cutoutCorners_; }
    // Benchmarks: how the main pass draws plants. Floor: the same triangles with a constant-colour fragment shader
    // (shaders/plant_floor.frag, the rasteriser's floor); Off: not at all. Truth and shadow passes are unchanged.
    enum class MainShading { Full, Floor, Off };
    void setMainShading(MainShading shading) { mainShading_ = shading; }
    // Benchmarks: while set, draw() wraps each tile's draw of each LOD in a statistics range named after the pass
    // and the LOD ("main.near", "truth.far", "shadow.mid", ...; drawBaked: "main.static"). The command buffers draw() then records into must
    // not dispatch compute (lavapipe crashes).
    void setStatistics(PipelineStatistics* statistics) { statistics_ = statistics; }
    // Live changes from the viewer's panel; used by the next expand().
    void setWindAndLod(const WindParams& wind, const LodParams& lod) {
        scene_.wind = wind;
        scene_.lod = lod;
    }
    // The records of the only resident tile (one-tile scenes: what the simulation updates).
    VegetationBuffers& buffers();
    // The records of resident tile `coord` (a world's simulation updates those of the tiles colliders touch).
    VegetationBuffers& buffers(TileCoord coord);
    uint32_t instanceCapacity() const { return capacity_; }
    // The atlas level a shadow cascade with texels of `texelMetres` reads its plants' alpha from, one for the whole
    // draw (FrameConstants::shadowParams.w): atlasLevelForTexel for the shortest category's base height, so no
    // plant's shadow is coarser than the map.
    uint32_t shadowAtlasLevel(double texelMetres) const;
    // The instance pool, for tests that read a one-tile expansion back.
    const Buffer& instances() const { return instances_; }

private:
    // A resident tile: its records and what its expansion writes besides the shared pool.
    struct Tile {
        Tile(Context& ctx, const VegetationTile& tile, uint64_t constantsBytes);
        ~Tile();
        Context& ctx;
        TileCoord coord;
        glm::dvec2 boundsMin, boundsMax; // xy of the tile: its plants' roots lie in it
        VegetationBuffers buffers;
        Buffer constants, clusterCounts, draws, stats;
        // The clusters' boxes, and per frame slot the order the expansion lays their instances out in (frontToBack
        // from the camera): written by the CPU each frame, read by the scan.
        std::vector<ClusterBox> clusterBoxes;
        Buffer clusterOrder;
        uint64_t orderStride = 0;
        bool expanded = false; // by the latest expand(): within reach of the camera; draw() draws only these
        Buffer keptStates[2];  // PlantDynamic[plants] of two earlier ticks (enableFlow())
    };
    using TileKey = std::pair<int32_t, int32_t>; // (y, x): the map iterates in the frame's tile order

    void uploadAtlas(const Atlas& atlas);
    void uploadCutoutBuffers(); // what cutoutCorners_ decides: cellTables_[cutoutCorners_] and the plant index buffers
    PipelineLayoutDesc drawLayout(bool withShadowMap) const; // the plant draws' layout: main (shadow map) or not
    // `farBillboards`: plant.frag's FAR_BILLBOARDS, whether the draws may hold far billboards.
    GraphicsPipelineDesc mainPipelineDesc(const char* fragmentShader, bool farBillboards = true) const;
    GraphicsPipelineDesc truthPipelineDesc() const; // the truth pass's plant draw (without flow)
    // The near blades' pipeline for `pass` (vegetation_blades.cpp), made on first use.
    const Pipeline& bladePipeline(PlantPass pass);
    // The categories drawn as blades (bit c: category c), those the atlas paints as grass.
    uint32_t bladeCategories() const;
    // The tile's expansion inputs for this frame slot: its constants and its clusters' frontToBack order.
    void writeConstants(const Tile& tile, const Camera& camera, double timeSeconds, uint32_t slot,
                        const std::array<glm::vec4, 5>& planes);
    void expandTile(VkCommandBuffer cmd, const Tile& tile, uint32_t slot, bool firstTile);
    bool withinReach(const Tile& tile, const glm::dvec3& camera) const;
    Tile& onlyTile();
    void startKeptStates(Tile& tile); // both kept states the live records (waits)
    DescriptorBinding constantsBinding(const Tile& tile, uint32_t slot) const;
    DescriptorBinding atlasCellsBinding() const;
    DescriptorBinding atlasBinding() const;

    Context& ctx_;
    Scene scene_;
    std::map<TileKey, std::unique_ptr<Tile>> tiles_;
    uint32_t capacity_ = 0;
    uint32_t atlasMaxColumns_ = 1;
    glm::uvec4 atlasColumns_{1u};
    glm::vec4 cardCover_{0.0f};   // cardCover(atlas): far slicing's card area per category
    glm::vec4 meanAspects_{0.0f}; // meanAspects(atlas): far merging's width per height per category
    uint32_t atlasCellHeight_ = 1; // texels of a cell's height at level 0
    uint32_t atlasLevels_ = 1;     // mip levels
    Buffer instances_, instancePlants_, cursor_, atlasCells_;
    // Each LOD's indices for one plant (plantFirstIndex), uint32: its quads' corners (plantIndex), for every pass.
    Buffer cornerIndices_;
    uint64_t constantsStride_ = 0;
    Image atlasImage_;
    VkSampler atlasSampler_ = VK_NULL_HANDLE;
    Pipeline countPipeline_, scanPipeline_, writePipeline_;
    Pipeline mainPipeline_, mainFarPipeline_, truthPipeline_, shadowPipeline_; // main: near and mid; mainFar: far
    Pipeline truthFlowPipeline_;                             // enableFlow()
    std::array<Pipeline, 4> bladePipelines_;                 // by PlantPass; bladePipeline()
    uint32_t latestKept_ = 0;                                // the tiles' kept state recordKeepState() wrote last
    Pipeline bakePipeline_, staticPipeline_, floorPipeline_; // created on first use (benchmarks, tests)
    MainShading mainShading_ = MainShading::Full;
    VegetationPassFormats formats_;
    PipelineStatistics* statistics_ = nullptr;
    uint32_t cutoutCorners_ = 0;
    std::vector<uint32_t> orderScratch_; // writeConstants: a tile's frontToBack order, kept between frames
    // The atlas cell table with each cut-out corner count's polygons (index = corners; 0: the whole cells).
    std::array<std::vector<gpu::AtlasCellGpu>, gpu::kMaxCutoutCorners + 1> cellTables_;
};

} // namespace sward
