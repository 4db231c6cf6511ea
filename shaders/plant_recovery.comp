#version 460
#extension GL_GOOGLE_include_directive : require
// Interaction update of one fixed tick, for active fields only (paper 3.4: the GPU animates what the CPU
// collision pass touched until it has recovered):
//   CONTACT_PASS = 1  one invocation per contact: apply it to its plant's dynamic record
//   CONTACT_PASS = 0  one invocation per plant of each active field (workgroup row y = active field):
//                     one step of the damped spring, written back to the dynamic buffer
#include "shared/config.h"
#include "shared/gpu_layout.h"
#include "shared/plant_layout.h"
#include "shared/recovery.glsl"

layout(constant_id = 0) const uint CONTACT_PASS = 0;
layout(local_size_x = kComputeGroupSize) in;

layout(set = 0, binding = kRecoveryBindingDynamics, std430) buffer Dynamics { PlantDynamic dynamics[]; };
layout(set = 0, binding = kRecoveryBindingContacts, std430) readonly buffer Contacts { PlantContact contacts[]; };
layout(set = 0, binding = kRecoveryBindingActiveFields, std430) readonly buffer ActiveFields { uvec2 activeFields[]; }; // first plant, count
layout(push_constant) uniform Push { RecoveryConstants params; } push;

void main() {
    if (CONTACT_PASS == 1u) {
        uint i = gl_GlobalInvocationID.x;
        if (i >= push.params.range.z) return;
        PlantContact contact = contacts[i];
        dynamics[contact.plant] = applyContact(dynamics[contact.plant], contact);
        return;
    }
    uvec2 field = activeFields[gl_WorkGroupID.y];
    uint i = gl_GlobalInvocationID.x;
    if (i >= field.y) return;
    dynamics[field.x + i] = recoverStep(dynamics[field.x + i], push.params);
}
