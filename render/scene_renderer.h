// SceneRenderer: draws a scene (terrain, vegetation, sky) into render targets.
//
// Passes per frame (see docs/architecture.md):
//   expansion   compute: cull clusters, choose LODs, write plant instances + indirect draws
//   shadow      D32 cascaded sun shadow maps side by side (terrain + objects + alpha-tested plants), orthographic,
//               fitted around distance shells of the camera's frustum (world/sun_shadow.h)
//   main        RGBA16F linear HDR radiance, 1x or 4x MSAA (alpha-to-coverage), resolved by averaging
//   truth       R32_UINT bit pattern of the planar depth in metres (+inf for sky), R32G32_UINT (label, tile) and
//               RGBA32F camera-frame triangle normal (0 for sky), always 1x: the same geometry rasterised once
//               at each pixel centre, so ground truth is exact and never a blend of two surfaces ("flying
//               pixels"), whatever the colour pass's sample count.
#pragma once

#include "dataset/frame_images.h"
#include "engine/context.h"
#include "engine/pipelines.h"
#include "engine/render_target.h"
#include "render/sky_constants.h"
#include "render/vegetation_renderer.h"
#include "scene/scene.h"
#include "vegetation/atlas.h"
#include "vegetation/cover_map.h"
#include "vegetation/vegetation_tile.h"
#include "world/camera.h"
#include "world/ground.h"
#include "world/sun_shadow.h"

#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <utility>

namespace sward {

class GpuTimers;
class GroundTracks;
class ObjectRenderer;
class TrackRenderer;
struct ObjectModel;
struct BakedPlants;

// TerrainTileConstants::material of a scene (gpu_layout.h): x terrain.material; y 1 when some category's
// ground_material differs from it (the tiles' ground material weights are read), else 0, so a scene whose categories
// have none, or the terrain's, draws exactly the terrain's material; z the categories' materials, 8 bits each.
glm::uvec4 groundMaterialConstants(const Scene& scene);

// Formats and clear values of the passes, in attachment order.
RenderTargetDesc mainPassTargetDesc(uint32_t width, uint32_t height, uint32_t samples);
// `flow`: with the two flow attachments (RGBA32F, forward then backward; shaders/shared/flow_fragment.glsl).
RenderTargetDesc truthPassTargetDesc(uint32_t width, uint32_t height, bool flow = false);

// Motion ground truth of a frame (the scene's render.flow; docs/dataset-format.md): the truth passes also write each
// pixel's flow to the next and to the previous tick. The views' truth targets need truthPassTargetDesc(.., true).
struct FlowTicks {
    std::array<const Camera*, 2> previous{}, next{}; // each view's camera at the previous and the next tick
    double timeStep = 0.0;                           // those ticks are at the frame's time -+ this
    // Records the next tick, between the main passes and the truth passes, which read its plant states as the next
    // tick's (the plants' state of this tick kept first: VegetationRenderer::recordKeepState).
    std::function<void(VkCommandBuffer)> beforeTruth;
};

class SceneRenderer {
public:
    // vegetation / atlas may be null (bare terrain). The tile and atlas are uploaded; the CPU copies may go.
    // The scene's objects are drawn from `models` (loadObjectModels) or, when null, models loaded here.
    // `terrain` must outlive the renderer (objects are placed on it every frame).
    // `cover` (makeCoverMap) shades the ground beyond the far LOD limit with the vegetation's look; null: bare.
    SceneRenderer(Context& ctx, const Scene& scene, const Ground& terrain, VkSampleCountFlagBits samples,
                  const VegetationTile* vegetation = nullptr, const Atlas* atlas = nullptr,
                  const std::vector<ObjectModel>* models = nullptr, const CoverMap* cover = nullptr);
    // A world (scene.world, procedural ground): starts with no tile; the owner of the WorldTiles adds
    // and removes tiles as they become resident. `atlas` null: bare ground. Only tiles within
    // world.view_distance (<= load_radius, within which WorldTiles keeps every tile resident) of the reference
    // camera are drawn, so a frame is the same whichever tiles beyond it happen to be resident. The scene's objects
    // (`models`: loadObjectModels; required with objects) each stand on their own lattice ground (objectGround).
    SceneRenderer(Context& ctx, const Scene& scene, VkSampleCountFlagBits samples, const Atlas* atlas,
                  const std::vector<ObjectModel>* models = nullptr);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // One view of a frame: its camera, colour target and (optional) ground-truth target.
    struct View {
        const Camera* camera;
        RenderTarget* main; // null: no colour pass (the truth alone)
        RenderTarget* truth = nullptr;
    };
    static constexpr uint32_t kMaxViews = 2;

    // Records the whole frame into `cmd`. `frameIndex` selects the constants slot (modulo gpu::kFrameDataSlots),
    // so frames may be in flight. `truth` may be null (viewer). Timers (optional) get one entry per pass.
    void record(VkCommandBuffer cmd, RenderTarget& main, RenderTarget* truth, const Camera& camera, double timeSeconds,
                uint32_t frameIndex, GpuTimers* timers = nullptr);
    // One instant seen by a rectified stereo rig (views[1] = views[0] moved along its own +x axis) or a single
    // view. The vegetation is expanded once — LODs, cross-fades and billboard orientation from views[0]'s
    // position, culling against the union of the frusta — and the sun shadow map is rendered once, so both
    // eyes see exactly the same geometry and shadows (a stereo matcher must not be shown two scenes).
    // `expand` false: the expansion is left out, recorded before by recordExpansion() for the same views, time and
    // frame (benchmarks count pipeline statistics in a command buffer without compute: lavapipe crashes otherwise).
    // `flow`: the truth passes with motion ground truth (a scene with render.flow; the vegetation's enableFlow() first).
    void recordViews(VkCommandBuffer cmd, std::span<const View> views, double timeSeconds, uint32_t frameIndex,
                     GpuTimers* timers = nullptr, bool expand = true, const FlowTicks* flow = nullptr);
    // The expansion recordViews() would record for these views, alone.
    void recordExpansion(VkCommandBuffer cmd, std::span<const View> views, double timeSeconds, uint32_t frameIndex,
                         GpuTimers* timers = nullptr);

    // Benchmark variant: expansion (unless `baked` is given) and the main pass only, no shadow or truth pass.
    // With `baked`, the plants are drawn from those static vertices instead of this frame's expansion.
    // Requires one full record() before (the shadow map must hold a frame).
    void recordMainOnly(VkCommandBuffer cmd, RenderTarget& main, const Camera& camera, double timeSeconds,
                        uint32_t frameIndex, GpuTimers* timers, const BakedPlants* baked);

    // Viewer hooks (sward-view): gpu::kDebug* flags for FrameConstants::debug.x, and an overlay recorded into
    // every main colour pass after the scene (before the resolve), given that pass's frame-constants binding.
    void setDebugFlags(uint32_t flags) { debugFlags_ = flags; }
    using Overlay = std::function<void(VkCommandBuffer, const DescriptorBinding& frame)>;
    void setMainPassOverlay(Overlay overlay) { overlay_ = std::move(overlay); }

    // Tiles: the ground (and its plants and far cover, when given) of tile `coord`, uploaded (waits). A one-tile
    // scene's renderer holds the tile (0, 0) from its construction.
    void addTile(TileCoord coord, const Ground& ground, const VegetationTile* plants, const CoverMap* cover);
    void removeTile(TileCoord coord); // freed once the frames in flight are done
    bool hasTile(TileCoord coord) const { return tiles_.contains(TileKey(coord.y, coord.x)); }
    uint32_t tileCount() const { return uint32_t(tiles_.size()); }
    std::vector<TileCoord> tiles() const; // (y, x) order

    // The ruts to draw (a scene whose colliders press them, sceneMakesRuts), pressed into `ground`; both must outlive
    // the renderer. Each frame uploads the blocks changed since the last one.
    void setGroundTracks(const GroundTracks* tracks, const Ground* ground);
    // A world's ruts (render/world_simulation.h), drawn over every tile within the view distance; `tracks` must
    // outlive the renderer.
    void setWorldGroundTracks(const GroundTracks* tracks);

    VegetationRenderer* vegetation() { return vegetation_.get(); }
    // The wind, sun and sky of the next frames (a program's change between frames, render/session.h): the sky's
    // constants are computed again.
    void setWeather(const WindParams& wind, const SunParams& sun, const SkyParams& sky) {
        scene_.wind = wind, scene_.sun = sun, scene_.sky = sky;
        writeSkyConstants(scene_, frameTemplate_);
        if (vegetation_) vegetation_->setWind(wind);
    }
    ObjectRenderer* objects() { return objects_.get(); } // null when the scene has no objects
    uint32_t samples() const { return samples_; }
    bool world() const { return std::isfinite(viewDistance_); } // a world of several tiles
    uint32_t horizonTriangles() const; // the world's horizon ring (render/horizon_ring.h); 0 without one

private:
    // A resident tile's ground: its mesh and its far cover (1x1 "nothing" without one, so the binding is valid).
    struct TerrainTile {
        Buffer vertices, indices;
        uint32_t indexCount = 0;
        Image cover, groundWeights; // groundWeights: CoverMap::groundWeights (1x1 zero without)
        glm::vec4 coverRect{0.0f};
        bool groundMaterials = false;              // the tile has ground material weights
        glm::dvec2 boundsMin{0.0}, boundsMax{0.0}; // xy
    };
    using TileKey = std::pair<int32_t, int32_t>; // (y, x): the drawing order

    void createPipelines(const Atlas* atlas, uint32_t instanceCapacity);
    VegetationPassFormats plantPassFormats() const;
    // The frame's sun shadow cascades, fitted once to the reference camera (both views of a stereo pair use them).
    struct ShadowFit {
        std::vector<ShadowCascade> cascades;
        glm::dvec3 origin{0.0}; // the reference camera's position: each point's cascade follows its distance to it
    };
    ShadowFit fitShadows(const Camera& reference) const;
    // Frame constants of `camera` with the frame's shadow cascades; `shadowDraw` >= 0 makes the slot the one the
    // shadow pass draws cascade `shadowDraw` with.
    // `flow`: also view `view`'s cameras at the previous and next tick (the truth pass with flow).
    void writeConstants(uint32_t slot, const Camera& camera, const ShadowFit& shadow, double timeSeconds,
                        int shadowDraw = -1, const FlowTicks* flow = nullptr, uint32_t view = 0);
    // The shadow pass: each cascade into its tile of the shadow map, with the plants' LODs that can reach it.
    void recordShadowPass(VkCommandBuffer cmd, const Camera& reference, const ShadowFit& shadow, uint32_t firstSlot,
                          uint32_t dataSlot, double timeSeconds, GpuTimers* timers);
    ShadowCascadeParams makeShadowCascadeParams(bool vegetation) const;
    void fitShadowImage(bool vegetation); // shadowParams_; throws if the device cannot hold the shadow image
    void createShadowMap();
    bool tileDrawn(const TerrainTile& tile, const glm::dvec3& reference) const; // within the view distance
    // A world's horizon ring (render/horizon_ring.cpp): made by the world constructor, drawn after the tiles.
    void addHorizonRing(const Atlas* atlas);
    void drawHorizonRing(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame);
    void releaseHorizonRing();
    // The tiles' ground within the view distance of `reference`; the main pass binds each tile's cover.
    void drawTerrain(VkCommandBuffer cmd, PlantPass pass, const DescriptorBinding& frame, const glm::dvec3& reference);
    // `frameSlot`: frame-constants slot (frame x view); `slot`: vegetation constants slot (frame).
    void recordMainPass(VkCommandBuffer cmd, RenderTarget& main, uint32_t frameSlot, uint32_t slot,
                        const glm::dvec3& reference, GpuTimers* timers, const BakedPlants* baked);
    DescriptorBinding frameBinding(uint32_t slot) const;
    DescriptorBinding shadowBinding() const;
    void uploadCoverMap(TerrainTile& tile, const CoverMap* cover);
    void uploadGroundTextures(const Ground* terrain);

    Context& ctx_;
    Scene scene_;
    // Every frame's constants start from this: the sky's fields (writeSkyConstants: the physical sky's coefficients
    // and its ambient light, a 384-direction integral), filled once from the scene, whose sun and sky never change.
    gpu::FrameConstants frameTemplate_{};
    uint32_t samples_ = 1;
    std::map<TileKey, TerrainTile> tiles_;
    double viewDistance_ = INFINITY; // world.view_distance in a world
    std::unique_ptr<TerrainTile> horizon_; // a world's horizon ring (world.horizon)
    float terrainMinHeight_ = 0.0f, terrainMaxHeight_ = 0.0f;
    const Ground* objectGround_ = nullptr; // what objects stand on (one-tile scenes)
    // Frame constants per data slot: one per view, then one per shadow cascade (the shadow pass's draws).
    static constexpr uint32_t kSlotsPerFrame = kMaxViews + gpu::kMaxShadowCascades;
    Buffer constants_; // gpu::kFrameDataSlots * kSlotsPerFrame slots of FrameConstants, host-visible
    uint64_t constantsStride_ = 0;
    Pipeline terrainPipeline_, terrainTruthPipeline_, terrainShadowPipeline_, skyPipeline_;
    Pipeline terrainTruthFlowPipeline_; // render.flow
    std::unique_ptr<RenderTarget> shadowMap_;
    ShadowCascadeParams shadowParams_; // fixed once the vegetation is known
    VkSampler shadowSampler_ = VK_NULL_HANDLE;
    VkSampler coverSampler_ = VK_NULL_HANDLE;
    Image groundTextures_; // a mesh ground's base-colour textures (one white layer without any)
    VkSampler groundSampler_ = VK_NULL_HANDLE;
    std::unique_ptr<VegetationRenderer> vegetation_;
    std::unique_ptr<ObjectRenderer> objects_;
    std::unique_ptr<TrackRenderer> tracks_; // a scene whose colliders press ruts
    uint32_t debugFlags_ = 0;
    Overlay overlay_;
};

// Targets and readback buffers for rendering frames of one size to host images, reused across a sequence.
class OffscreenFrame {
public:
    // `flow`: truth targets with the flow attachments, for render() with FlowTicks.
    OffscreenFrame(Context& ctx, uint32_t width, uint32_t height, uint32_t samples, bool flow = false);
    ~OffscreenFrame();
    OffscreenFrame(const OffscreenFrame&) = delete;
    OffscreenFrame& operator=(const OffscreenFrame&) = delete;

    // Records `prologue` (e.g. the interaction tick), the frame and the readbacks in one submission and waits.
    // With `right`, also renders the right view of a stereo rig (see SceneRenderer::recordViews), colour and
    // ground truth.
    // `flow` (an OffscreenFrame made with flow): the truth passes write the motion ground truth, read back too.
    // `colour` false: no colour pass and no colour image (rgbaHalf empty): the truth of a frame whose colour comes
    // from an exposure's sub-frames (render/motion_blur.h).
    FrameImages render(SceneRenderer& renderer, const Camera& camera, double timeSeconds, uint32_t frameIndex,
                       const std::function<void(VkCommandBuffer)>& prologue = {}, const Camera* right = nullptr,
                       const FlowTicks* flow = nullptr, bool colour = true);
    // The colour images alone (no truth pass) into `left` and, with `right`, `rightRgba` (half bit patterns).
    void renderColour(SceneRenderer& renderer, const Camera& camera, double timeSeconds, uint32_t frameIndex,
                      const std::function<void(VkCommandBuffer)>& prologue, const Camera* right,
                      std::vector<uint16_t>& left, std::vector<uint16_t>* rightRgba);

private:
    void createRightTargets(); // on the first stereo frame

    Context& ctx_;
    RenderTarget main_, truth_;
    std::unique_ptr<RenderTarget> rightMain_, rightTruth_; // created on the first stereo frame
    Buffer color_, depth_, labels_, normals_, rightColor_, rightDepth_, rightLabels_, rightNormals_;
    Buffer flow_[2], rightFlow_[2]; // forward, backward (made with flow)

public:
    bool hasFlow() const { return bool(flow_[0]); }
};

// Renders one frame into fresh targets (the renderer's sample count) and reads colour and depth back (waits).
FrameImages renderFrame(Context& ctx, SceneRenderer& renderer, const Camera& camera, double timeSeconds = 0.0);

} // namespace sward
