// GPU struct layouts and constants shared by C++ and GLSL. One definition, two languages:
// in C++ the structs live in namespace sward::gpu with glm types and their sizes are static_assert'ed;
// in GLSL the same text declares the std140/std430 block members. Use only vec4/mat4/uvec4-aligned members
// (or scalars packed into them) so std140, std430 and C++ agree without padding rules to remember.
#ifndef SWARD_GPU_LAYOUT_H
#define SWARD_GPU_LAYOUT_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstdint>
namespace sward::gpu {
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#define SWARD_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_CONST(type, name, value) const type name = value
#endif

// Workgroup sizes (also used as specialization-constant defaults).
SWARD_CONST(uint, kComputeGroupSize, 64u);

// Ground-truth depth is written as the bit pattern of a float into an R32_UINT attachment, so that the MSAA
// resolve can pick sample 0 (integer formats resolve with SAMPLE_ZERO; float formats could only average,
// which would blend foreground and background into "flying pixels"). Sky keeps the clear value: +inf.
SWARD_CONST(uint, kDepthInfinityBits, 0x7f800000u);

// Per-frame constants (uniform buffer, set 0 binding 0).
struct FrameConstants {
    mat4 viewProj;       // world -> clip (reversed Z, infinite far plane)
    mat4 view;           // world -> camera, OpenCV axes (x right, y down, z forward)
    mat4 invViewProj;    // clip -> world, for sky rays
    vec4 cameraPosition; // xyz world position, w unused
    vec4 sunDirection;   // xyz unit vector towards the sun, w unused
    vec4 sunRadiance;    // rgb, linear, w unused
    vec4 skyZenith;      // rgb radiance at the zenith
    vec4 skyHorizon;     // rgb radiance at the horizon
    vec4 groundAmbient;  // rgb radiance from below the horizon
    vec4 viewport;       // width, height, 1/width, 1/height
    vec4 timeParams;     // x simulation time in seconds, yzw reserved
};

// Vertex of the terrain mesh (vertex buffer, binding 0).
struct TerrainVertex {
    vec4 positionHeight; // xyz world position, w unused
    vec4 normal;         // xyz smooth normal, w unused
};

#ifdef __cplusplus
static_assert(sizeof(FrameConstants) == 3 * 64 + 8 * 16);
static_assert(sizeof(TerrainVertex) == 32);
} // namespace sward::gpu
#endif
#undef SWARD_CONST

#endif
