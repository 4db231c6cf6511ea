#version 460
#extension GL_GOOGLE_include_directive : require
// Engine self-test: out[i] = in[i] * SCALE + offset. Exercises storage buffers through push descriptors,
// push constants and a specialization constant.
#include "shared/config.h"

layout(constant_id = 0) const uint SCALE = 1;
layout(local_size_x = kComputeGroupSize) in;

layout(set = 0, binding = kTestBindingInput, std430) readonly buffer Input { uint values[]; } src;
layout(set = 0, binding = kTestBindingOutput, std430) writeonly buffer Output { uint values[]; } dst;
layout(push_constant) uniform Push { uint count; uint offset; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < push.count) dst.values[i] = src.values[i] * SCALE + push.offset;
}
