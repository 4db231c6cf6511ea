// Plant interaction dynamics per fixed tick: contacts from the CPU collision pass are applied, then a damped
// spring pulls every bent plant of an active field back to rest (paper 3.3-3.4). This file is the CPU
// reference of the GPU recovery pass (shaders/plant_recovery.comp with shaders/shared/recovery.glsl): the
// same float operations in the same order, with `precise` on the GPU so no FMA contraction can change a
// rounding. Records are quantised after every tick exactly as on the GPU.
#pragma once

#include "shared/gpu_layout.h"
#include "shared/plant_layout.h"

#include <cstdint>
#include <span>

namespace sward {

struct RecoveryParams {
    float timeStep = 1.0f / 30.0f; // seconds per tick (fixed)
    float stiffness = 40.0f;       // spring constant per unit bend, 1/s^2 (omega^2)
    float damping = 9.0f;          // 1/s; 2*sqrt(stiffness) is critical
    float restBend = 0.01f;        // |bend| and |velocity| below this snap to exact rest
    float fellBend = 0.9f;         // tip offset of felled plants (plant heights)
    uint32_t restTicks = 90;       // a field with no contact for this many ticks has recovered: inactive
};

// Contacts are gpu::PlantContact (shaders/shared/gpu_layout.h): one per touched plant and tick, sorted by plant.

// Applies one contact to one plant record (GPU: plant_recovery.comp, contact pass).
gpu::PlantDynamic applyContact(gpu::PlantDynamic record, const gpu::PlantContact& contact, const RecoveryParams& params);
// Advances one plant record by one tick (GPU: plant_recovery.comp, integration pass).
gpu::PlantDynamic recoverStep(gpu::PlantDynamic record, const RecoveryParams& params);
// True when the record is at exact rest (bend and velocity zero) or in a state that never changes (felled).
bool plantSettled(const gpu::PlantDynamic& record);

} // namespace sward
