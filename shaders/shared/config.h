// Numbers the CPU and the GPU share that are not struct layouts (niagara's config.h): workgroup sizes, frames
// in flight and render pass variants. One definition, two languages: in C++ the constants live in namespace
// sward::gpu; GLSL sees plain consts (valid in layout qualifiers: `layout(local_size_x = kComputeGroupSize)`).
// Struct layouts are in gpu_layout.h (which includes this header), descriptor binding slots in bindings.h.
// No glm here: the engine includes it for the frame counts.
#ifndef SWARD_CONFIG_H
#define SWARD_CONFIG_H

#ifdef __cplusplus
#include <cstdint>
namespace sward::gpu {
using uint = uint32_t;
#define SWARD_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_CONST(type, name, value) const type name = value
#endif

// Workgroup sizes: each compute shader's local_size_x and the C++ dispatch arithmetic (dispatchLinear).
SWARD_CONST(uint, kComputeGroupSize, 64u); // one invocation per element: recovery, bake, engine self-test
SWARD_CONST(uint, kExpandGroupSize, 64u);  // expansion: one invocation per plant cluster
SWARD_CONST(uint, kScanGroupSize, 1024u);  // single-workgroup scan over all clusters
// Workgroups a linear dispatch puts on x before it spills into y (the guaranteed maxComputeWorkGroupCount[0]).
// The shader's linear index is then gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * size.
SWARD_CONST(uint, kMaxGroupsX, 65535u);

// Frames the CPU may record and submit while the GPU still executes earlier ones: the swapchain's ring of
// acquire semaphores and frame fences (a frame waits for the one kFramesInFlight before it) and the viewer's
// per-frame GPU timers.
SWARD_CONST(uint, kFramesInFlight, 2u);
// Ring slots of host-visible per-frame data (frame and vegetation constants, object transforms, interaction
// uploads, viewer overlay lines), indexed by frame (or tick) modulo this. One more than kFramesInFlight, so a
// frame may write its slot even before waiting for its frame fence: the slot's previous user, kFrameDataSlots
// frames back, was already waited for by the frame before.
SWARD_CONST(uint, kFrameDataSlots, kFramesInFlight + 1u);

// Render pass variant of the shaders shared by several passes (specialization constant PASS).
SWARD_CONST(uint, kPassMain, 0u);   // colour, lit and shadowed
SWARD_CONST(uint, kPassTruth, 1u);  // ground truth: depth bits and labels, one sample per pixel
SWARD_CONST(uint, kPassShadow, 2u); // sun shadow map: depth only, seen from the sun

#ifdef __cplusplus
} // namespace sward::gpu
#endif
#undef SWARD_CONST

#endif
