// ObjectRenderer: draws the scene's glTF objects (vegetation/objects.h) in the main colour, sun shadow and
// ground-truth passes.
//
// All objects share one vertex and one index buffer (node-frame vertices tagged with their node's transform
// index and their object's truth label), so each pass is one indexed draw. update() writes every node's world
// transform for a simulation time into one of gpu::kFrameDataSlots host-visible slots; the record*() calls
// draw into a rendering pass the caller has begun, with the same descriptor conventions as the terrain (push
// descriptors: gpu::kBindingFrame, gpu::kBindingShadowMap; gpu::kBindingObjectTransforms is the transforms).
#pragma once

#include "engine/context.h"
#include "engine/pipelines.h"
#include "render/vegetation_renderer.h" // VegetationPassFormats: the same pass formats
#include "scene/objects.h"
#include "scene/scene.h"
#include "world/ground.h"

namespace sward {

class ObjectRenderer {
public:
    // Loads the scene's models (errors name the JSON path) and uploads them. `terrain` must outlive the
    // renderer (update() places the objects on it). With no objects the renderer records nothing.
    ObjectRenderer(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationPassFormats& formats);
    // Same, with models already loaded by loadObjectModels(scene.objects, ...) (e.g. shared with the collision pass).
    ObjectRenderer(Context& ctx, const Scene& scene, const Ground& terrain, const VegetationPassFormats& formats,
                   std::vector<ObjectModel> models);
    // A world of several tiles (`world` must outlive the renderer): each object stands on its own lattice ground
    // (objectGround, scene/world_objects.h), whichever tiles are resident.
    ObjectRenderer(Context& ctx, const Scene& world, const VegetationPassFormats& formats,
                   std::vector<ObjectModel> models);
    ~ObjectRenderer();
    ObjectRenderer(const ObjectRenderer&) = delete;
    ObjectRenderer& operator=(const ObjectRenderer&) = delete;

    bool empty() const { return indexCount_ == 0; }
    uint32_t triangleCount() const { return indexCount_ / 3; }
    const std::vector<ObjectModel>& models() const { return models_; }

    // Places object k at world xy `position`, heading `headingRadians` (from +x towards +y), on the terrain,
    // instead of following its path (e.g. the rover driven from the keyboard in sward-view); hidden objects
    // collapse to a point and draw nothing. Applies from the next update().
    void place(size_t k, glm::dvec2 position, double headingRadians);
    // Every object's parameters (path, yaw) as given, all visible: a session's restart (render/session.h).
    void resetObjects(const std::vector<ObjectParams>& objects);
    void setVisible(size_t k, bool visible);

    // Writes the node transforms at simulation time `time` into slot `slot` (< gpu::kFrameDataSlots). The slot must not be
    // in use by a frame still executing on the GPU (the caller's frames-in-flight rotation guarantees this).
    // `flowTimes` (the truth pass with flow): also those at the previous and the next tick, after this time's.
    void update(double time, uint32_t slot = 0, const std::array<double, 2>* flowTimes = nullptr);
    uint32_t transformCount() const { return transformCount_; } // per time
    // Draw calls into the current pass; `slot` as given to update(). `frame` is the frame-constants binding.
    void recordMain(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& shadowMap,
                    uint32_t slot = 0);
    void recordShadow(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot = 0);
    // `flow`: the truth pass with motion ground truth (PlantPass::TruthFlow; the scene's render.flow).
    void recordTruth(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot = 0, bool flow = false);

private:
    ObjectRenderer(Context& ctx, const Scene& scene, const Ground* terrain, const VegetationPassFormats& formats,
                   std::vector<ObjectModel> models);
    void draw(VkCommandBuffer cmd, const Pipeline& pipeline, std::initializer_list<DescriptorBinding> bindings);
    DescriptorBinding transformsBinding(uint32_t slot) const;

    Context& ctx_;
    const Ground* terrain_; // null: a world's objects, each on its objectGround
    const Scene* world_ = nullptr;
    std::vector<ObjectParams> objects_;
    std::vector<ObjectModel> models_;
    std::vector<uint32_t> firstTransform_; // per object: index of its first node's transform
    std::vector<uint8_t> hidden_;          // per object
    uint32_t transformCount_ = 0, indexCount_ = 0;
    Buffer vertices_, indices_, transforms_;
    uint64_t transformsStride_ = 0;
    Pipeline mainPipeline_, shadowPipeline_, truthPipeline_, truthFlowPipeline_;
};

} // namespace sward
