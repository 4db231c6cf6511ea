#include "render/object_renderer.h"

#include "scene/world_objects.h"
#include "shared/config.h"
#include "shared/object_layout.h"

#include <cstring>
#include <optional>

namespace sward {

ObjectRenderer::ObjectRenderer(Context& ctx, const Scene& scene, const Ground& terrain,
                               const VegetationPassFormats& formats)
    : ObjectRenderer(ctx, scene, terrain, formats, loadObjectModels(scene.objects, scene.source)) {}

ObjectRenderer::ObjectRenderer(Context& ctx, const Scene& scene, const Ground& terrain,
                               const VegetationPassFormats& formats, std::vector<ObjectModel> models)
    : ObjectRenderer(ctx, scene, &terrain, formats, std::move(models)) {}

ObjectRenderer::ObjectRenderer(Context& ctx, const Scene& world, const VegetationPassFormats& formats,
                               std::vector<ObjectModel> models)
    : ObjectRenderer(ctx, world, nullptr, formats, std::move(models)) {}

ObjectRenderer::ObjectRenderer(Context& ctx, const Scene& scene, const Ground* terrain,
                               const VegetationPassFormats& formats, std::vector<ObjectModel> models)
    : ctx_(ctx), terrain_(terrain), world_(terrain ? nullptr : &scene), objects_(scene.objects),
      models_(std::move(models)) {
    require(terrain || scene.world.enabled, "ObjectRenderer: objects stand on a terrain or in a world");
    require(models_.size() == objects_.size(), "ObjectRenderer: one model per scene object is required");
    std::vector<gpu::ObjectVertex> vertices;
    std::vector<uint32_t> indices;
    for (size_t k = 0; k < objects_.size(); ++k) {
        firstTransform_.push_back(transformCount_);
        for (const ModelNode& node : models_[k].nodes) {
            for (const ModelPrimitive& prim : node.primitives) {
                const uint32_t base = uint32_t(vertices.size());
                for (size_t v = 0; v < prim.positions.size(); ++v)
                    vertices.push_back({glm::vec4(prim.positions[v], 1.0f), glm::vec4(prim.normals[v], 0.0f),
                                        prim.baseColor, glm::uvec4(transformCount_, objectLabel(k), 0u, 0u)});
                for (uint32_t index : prim.indices) indices.push_back(base + index);
            }
            ++transformCount_;
        }
    }
    indexCount_ = uint32_t(indices.size());
    if (empty()) return;

    // Storage too: the truth pass pulls whole triangles (object_truth.vert).
    vertices_ = createBufferWithData(ctx, bytesOf(vertices),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    indices_ = createBufferWithData(ctx, bytesOf(indices),
                                    VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const uint64_t align = ctx.device.properties().limits.minStorageBufferOffsetAlignment;
    // Three times per slot: this time's transforms, then the previous and the next tick's (the truth pass with flow).
    transformsStride_ = (3 * uint64_t(transformCount_) * sizeof(gpu::ObjectTransform) + align - 1) / align * align;
    transforms_ = createBuffer(ctx, transformsStride_ * gpu::kFrameDataSlots, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               MemoryIntent::Upload);

    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    PipelineLayoutDesc layout{
        .bindings = {layoutBinding(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, stages),
                     layoutBinding(gpu::kBindingObjectTransforms, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                   VK_SHADER_STAGE_VERTEX_BIT)}};
    PipelineLayoutDesc shadedLayout = layout; // + the sun shadow map
    shadedLayout.bindings.push_back(
        layoutBinding(gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT));
    GraphicsPipelineDesc desc{
        .vertexShader = "object.vert",
        .fragmentShader = "object.frag",
        .vertexBindings = {{0, sizeof(gpu::ObjectVertex), VK_VERTEX_INPUT_RATE_VERTEX}},
        .vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::ObjectVertex, position)},
                             {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::ObjectVertex, normal)},
                             {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::ObjectVertex, baseColor)},
                             {3, 0, VK_FORMAT_R32G32B32A32_UINT, offsetof(gpu::ObjectVertex, info)}},
        .cullMode = VK_CULL_MODE_BACK_BIT, // models are closed; the loader keeps fronts outside (mirrored nodes too)
        .colorFormats = {formats.mainColor},
        .depthFormat = formats.mainDepth,
        .samples = formats.mainSamples,
        .specialization = {/* PASS= */ gpu::kPassMain},
    };
    mainPipeline_ = createGraphicsPipeline(ctx.device, desc, shadedLayout);
    // Same triangles and rasterisation, pulled from storage buffers so each vertex knows its triangle's normal
    // (object_truth.vert); ground-truth outputs (depth bits, label, normal), one sample per pixel.
    GraphicsPipelineDesc truth = desc;
    truth.vertexShader = "object_truth.vert";
    truth.fragmentShader = "object_truth.frag";
    truth.vertexBindings = {};
    truth.vertexAttributes = {};
    truth.colorFormats = {formats.truthDepthBits, formats.truthLabel, formats.truthNormal};
    truth.depthFormat = formats.truthDepth;
    truth.samples = VK_SAMPLE_COUNT_1_BIT;
    truth.specialization = {/* PASS= */ gpu::kPassTruth};
    PipelineLayoutDesc truthLayout = layout; // + the pulled vertices and triangle list
    for (uint32_t binding : {gpu::kBindingMeshVertices, gpu::kBindingMeshIndices})
        truthLayout.bindings.push_back(
            layoutBinding(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT));
    truthPipeline_ = createGraphicsPipeline(ctx.device, truth, truthLayout);
    if (scene.render.flow)
        truthFlowPipeline_ =
            createGraphicsPipeline(ctx.device, truthFlowPipelineDesc(truth, formats.truthFlow), truthLayout);
    // Depth only from the sun, both faces and the terrain's bias: thin parts (mast, wheels) still cast shadows.
    desc.fragmentShader = "";
    desc.colorFormats = {};
    desc.depthFormat = formats.shadowDepth;
    desc.samples = VK_SAMPLE_COUNT_1_BIT;
    desc.cullMode = VK_CULL_MODE_NONE;
    desc.specialization = {/* PASS= */ gpu::kPassShadow};
    desc.depthBias = -1.0f;
    desc.depthBiasSlope = -1.5f;
    shadowPipeline_ = createGraphicsPipeline(ctx.device, desc, layout);
    for (uint32_t slot = 0; slot < gpu::kFrameDataSlots; ++slot)
        update(0.0, slot); // never draw uninitialised transforms
}

ObjectRenderer::~ObjectRenderer() {
    if (empty()) return;
    ctx_.submitter.waitIdle();
    destroyPipeline(ctx_.device, mainPipeline_);
    destroyPipeline(ctx_.device, truthPipeline_);
    destroyPipeline(ctx_.device, truthFlowPipeline_);
    destroyPipeline(ctx_.device, shadowPipeline_);
    destroyBuffer(ctx_, vertices_);
    destroyBuffer(ctx_, indices_);
    destroyBuffer(ctx_, transforms_);
}

void ObjectRenderer::place(size_t k, glm::dvec2 position, double headingRadians) {
    require(k < objects_.size(), "ObjectRenderer::place: no object " + std::to_string(k));
    // A one-point path faces +x; the yaw turns the model to the heading (objects.h).
    objects_[k].path.points = {position};
    objects_[k].yawDegrees = headingRadians * 180.0 / 3.14159265358979323846;
}

void ObjectRenderer::resetObjects(const std::vector<ObjectParams>& objects) {
    require(objects.size() == objects_.size(), "ObjectRenderer::resetObjects: another scene's objects");
    objects_ = objects;
    hidden_.clear();
}

void ObjectRenderer::setVisible(size_t k, bool visible) {
    require(k < objects_.size(), "ObjectRenderer::setVisible: no object " + std::to_string(k));
    hidden_.resize(objects_.size(), 0);
    hidden_[k] = visible ? 0 : 1;
}

void ObjectRenderer::update(double time, uint32_t slot, const std::array<double, 2>* flowTimes) {
    if (empty()) return;
    require(slot < gpu::kFrameDataSlots, "ObjectRenderer::update: slot out of range");
    std::vector<gpu::ObjectTransform> transforms;
    transforms.reserve(3 * size_t(transformCount_));
    std::vector<double> times{time};
    if (flowTimes) times.insert(times.end(), flowTimes->begin(), flowTimes->end());
    for (double t : times) {
        for (size_t k = 0; k < objects_.size(); ++k) {
            const bool hidden = k < hidden_.size() && hidden_[k];
            const std::optional<Ground> own =
                terrain_ ? std::nullopt : std::optional<Ground>(objectGround(*world_, objects_[k], models_[k], t));
            for (const glm::dmat4& m : objectNodeTransforms(objects_[k], models_[k], terrain_ ? *terrain_ : *own, t))
                transforms.push_back(
                    hidden ? gpu::ObjectTransform{glm::mat4(0.0f), glm::mat4(0.0f)}
                           : gpu::ObjectTransform{glm::mat4(m), glm::mat4(glm::transpose(glm::inverse(m)))});
        }
    }
    if (transforms.empty()) return; // memcpy from an empty vector's null data() is undefined
    std::memcpy(transforms_.mapped() + slot * transformsStride_, transforms.data(),
                transforms.size() * sizeof(gpu::ObjectTransform));
}

DescriptorBinding ObjectRenderer::transformsBinding(uint32_t slot) const {
    return storageBuffer(gpu::kBindingObjectTransforms, transforms_.handle, slot * transformsStride_,
                         3 * uint64_t(transformCount_) * sizeof(gpu::ObjectTransform));
}

void ObjectRenderer::draw(VkCommandBuffer cmd, const Pipeline& pipeline,
                          std::initializer_list<DescriptorBinding> bindings) {
    drawIndexedMesh(ctx_.device, cmd, pipeline, bindings, vertices_.handle, indices_.handle, indexCount_);
}

void ObjectRenderer::recordMain(VkCommandBuffer cmd, const DescriptorBinding& frame, const DescriptorBinding& shadowMap,
                                uint32_t slot) {
    if (!empty()) draw(cmd, mainPipeline_, {frame, transformsBinding(slot), shadowMap});
}

void ObjectRenderer::recordShadow(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot) {
    if (!empty()) draw(cmd, shadowPipeline_, {frame, transformsBinding(slot)});
}

void ObjectRenderer::recordTruth(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot, bool flow) {
    if (empty()) return;
    const Pipeline& pipeline = flow ? truthFlowPipeline_ : truthPipeline_;
    require(pipeline.handle, "ObjectRenderer::recordTruth: flow needs a scene with render.flow");
    bindPipeline(cmd, pipeline);
    pushDescriptors(ctx_.device, cmd, pipeline,
                    {frame, transformsBinding(slot), storageBuffer(gpu::kBindingMeshVertices, vertices_.handle),
                     storageBuffer(gpu::kBindingMeshIndices, indices_.handle)});
    vkCmdDraw(cmd, indexCount_, 1, 0, 0); // non-indexed: the shader reads the triangle list
}

} // namespace sward
