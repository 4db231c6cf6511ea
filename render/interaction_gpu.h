// InteractionGpu: the GPU half of interaction (paper 3.4). Per fixed tick it uploads the CPU collision pass's
// contacts (16 bytes per touched plant, nothing else) and the ranges of the active fields, applies the
// contacts to the dynamic records and advances the damped spring of every plant in an active field.
// Fields that are not active are never dispatched; with no active field nothing is recorded at all.
#pragma once

#include "engine/context.h"
#include "engine/pipelines.h"
#include "interaction/recovery.h"
#include "interaction/tick_contacts.h"
#include "render/vegetation_buffers.h"
#include "shared/config.h"

#include <span>
#include <vector>

namespace sward {

class GpuTimers;

struct InteractionGpuStats {
    uint64_t dispatches = 0;       // recovery + contact dispatches recorded so far
    uint64_t fieldsDispatched = 0; // sum over ticks of active fields dispatched
    uint64_t uploadBytes = 0;      // contact + active-range bytes written for the GPU so far
    double uploadMs = 0.0;         // wall time of those writes (into host-visible memory the shader reads)
};

class InteractionGpu {
public:
    InteractionGpu(Context& ctx, VegetationBuffers& buffers);
    ~InteractionGpu();
    InteractionGpu(const InteractionGpu&) = delete;
    InteractionGpu& operator=(const InteractionGpu&) = delete;

    // Records one tick: contacts (sorted by plant, at most one per plant), then one spring step for every plant
    // of the active fields (field indices into the tile). `slot` selects the upload ring slot (taken modulo
    // gpu::kFrameDataSlots).
    void record(VkCommandBuffer cmd, const TickContacts& contacts, std::span<const uint32_t> activeFields,
                const RecoveryParams& params, uint32_t slot, GpuTimers* timers = nullptr);

    // Copies of the whole dynamic record buffer (waits for the GPU): for save / restore and tests.
    std::vector<gpu::PlantDynamic> readDynamics();
    void writeDynamics(std::span<const gpu::PlantDynamic> dynamics);

    const InteractionGpuStats& stats() const { return stats_; }

    // The upload ring's size; sward-view still names it here (tools/sward-view/viewer.cpp).

private:
    struct Slot {
        Buffer contacts, ranges; // host-visible: written by the CPU, read by the shader, no staging copy
    };
    void reserve(Slot& slot, uint64_t contactBytes, uint64_t rangeBytes);

    Context& ctx_;
    VegetationBuffers& buffers_;
    std::vector<uint32_t> fieldFirstPlant_, fieldPlantCount_;
    Slot slots_[gpu::kFrameDataSlots];
    Pipeline contactPipeline_, recoveryPipeline_;
    InteractionGpuStats stats_;
};

} // namespace sward
