#include "render/interaction_gpu.h"

#include "common/stopwatch.h"

#include "engine/barriers.h"
#include "engine/timestamps.h"
#include "shared/config.h"

#include <algorithm>
#include <cstring>

namespace sward {

InteractionGpu::InteractionGpu(Context& ctx, VegetationBuffers& buffers) : ctx_(ctx), buffers_(buffers) {
    // The field table (first plant, count) is needed on the CPU to build the active ranges.
    std::vector<uint8_t> bytes = readBuffer(ctx, buffers.fields, 0, uint64_t(buffers.fieldCount) * sizeof(gpu::PlantField));
    std::vector<gpu::PlantField> fields(buffers.fieldCount);
    if (!bytes.empty()) std::memcpy(fields.data(), bytes.data(), bytes.size()); // data() may be null when empty
    for (const gpu::PlantField& f : fields) {
        fieldFirstPlant_.push_back(f.range.x);
        fieldPlantCount_.push_back(f.range.y);
    }
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    PipelineLayoutDesc layout{
        .bindings = {layoutBinding(gpu::kRecoveryBindingDynamics, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs),
                     layoutBinding(gpu::kRecoveryBindingContacts, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs),
                     layoutBinding(gpu::kRecoveryBindingActiveFields, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs)},
        .pushConstantSize = sizeof(gpu::RecoveryConstants),
        .pushConstantStages = cs};
    contactPipeline_ = createComputePipeline(ctx.device, "plant_recovery.comp", layout, {/* CONTACT_PASS= */ 1});
    recoveryPipeline_ = createComputePipeline(ctx.device, "plant_recovery.comp", layout, {/* CONTACT_PASS= */ 0});
    for (Slot& slot : slots_) reserve(slot, 4096, 4096);
}

InteractionGpu::~InteractionGpu() {
    ctx_.submitter.waitIdle();
    destroyPipeline(ctx_.device, contactPipeline_);
    destroyPipeline(ctx_.device, recoveryPipeline_);
    for (Slot& slot : slots_) {
        destroyBuffer(ctx_, slot.contacts);
        destroyBuffer(ctx_, slot.ranges);
    }
}

void InteractionGpu::reserve(Slot& slot, uint64_t contactBytes, uint64_t rangeBytes) {
    auto grow = [&](Buffer& buffer, uint64_t bytes) {
        if (buffer && buffer.size >= bytes) return;
        retireBuffer(ctx_, buffer); // the GPU may still read the old one
        buffer = createBuffer(ctx_, std::max<uint64_t>(bytes * 2, 4096), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryIntent::Upload);
    };
    grow(slot.contacts, contactBytes);
    grow(slot.ranges, rangeBytes);
}

void InteractionGpu::record(VkCommandBuffer cmd, const TickContacts& contacts, std::span<const uint32_t> activeFields,
                            const RecoveryParams& params, uint32_t slotIndex, GpuTimers* timers) {
    if (contacts.empty() && activeFields.empty()) return; // idle grass costs nothing
    const Stopwatch upload;
    Slot& slot = slots_[slotIndex % gpu::kFrameDataSlots];
    uint64_t contactBytes = contacts.size() * sizeof(gpu::PlantContact);
    uint64_t rangeBytes = activeFields.size() * sizeof(glm::uvec2);
    reserve(slot, contactBytes, rangeBytes);
    contacts.copyTo({reinterpret_cast<gpu::PlantContact*>(slot.contacts.mapped()), contacts.size()});
    auto* ranges = reinterpret_cast<glm::uvec2*>(slot.ranges.mapped());
    uint32_t maxPlants = 0;
    for (size_t i = 0; i < activeFields.size(); ++i) {
        uint32_t f = activeFields[i];
        require(f < fieldFirstPlant_.size(), "active field index out of range");
        ranges[i] = {fieldFirstPlant_[f], fieldPlantCount_[f]};
        maxPlants = std::max(maxPlants, fieldPlantCount_[f]);
    }
    stats_.uploadBytes += contactBytes + rangeBytes;
    stats_.uploadMs += upload.ms();

    gpu::RecoveryConstants constants{
        .spring = glm::vec4(params.timeStep, params.stiffness, params.damping, params.restBend),
        .fell = glm::vec4(params.fellBend, 0.0f, 0.0f, 0.0f),
        .range = glm::uvec4(0, 0, uint32_t(contacts.size()), 0),
    };
    auto bind = [&](const Pipeline& pipeline) {
        bindPipeline(cmd, pipeline);
        pushDescriptors(ctx_.device, cmd, pipeline,
                        {storageBuffer(gpu::kRecoveryBindingDynamics, buffers_.dynamics.handle),
                         storageBuffer(gpu::kRecoveryBindingContacts, slot.contacts.handle),
                         storageBuffer(gpu::kRecoveryBindingActiveFields, slot.ranges.handle)});
        pushConstants(cmd, pipeline, constants);
    };
    if (timers) timers->begin(cmd, "recovery");
    // Earlier readers and writers of the dynamic records (last frame's expansion, last tick's recovery, uploads).
    computeAndCopyToComputeBarrier(cmd);
    if (!contacts.empty()) {
        bind(contactPipeline_);
        vkCmdDispatch(cmd, groupCount(uint32_t(contacts.size()), gpu::kComputeGroupSize), 1, 1);
        ++stats_.dispatches;
        computeToComputeBarrier(cmd);
    }
    if (!activeFields.empty() && maxPlants > 0) {
        bind(recoveryPipeline_); // workgroup row y = active field
        vkCmdDispatch(cmd, groupCount(maxPlants, gpu::kComputeGroupSize), uint32_t(activeFields.size()), 1);
        ++stats_.dispatches;
        stats_.fieldsDispatched += activeFields.size();
    }
    // The expansion (compute) and readbacks (copy) read the updated records.
    computeToComputeAndCopyBarrier(cmd);
    if (timers) timers->end(cmd);
}

std::vector<gpu::PlantDynamic> InteractionGpu::readDynamics() {
    std::vector<gpu::PlantDynamic> out(buffers_.plantCount);
    std::vector<uint8_t> bytes = readBuffer(ctx_, buffers_.dynamics, 0, out.size() * sizeof(gpu::PlantDynamic));
    if (!bytes.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

void InteractionGpu::writeDynamics(std::span<const gpu::PlantDynamic> dynamics) {
    require(dynamics.size() == buffers_.plantCount, "restored dynamic state has " + std::to_string(dynamics.size()) +
                                                        " plants, the tile has " + std::to_string(buffers_.plantCount));
    uploadToBuffer(ctx_, buffers_.dynamics, 0,
                   {reinterpret_cast<const uint8_t*>(dynamics.data()), dynamics.size_bytes()});
}

} // namespace sward
