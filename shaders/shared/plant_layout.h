// Compact per-plant records and per-cluster/per-field metadata shared by C++ and GLSL (issue 4).
// Same pattern as gpu_layout.h: in C++ the structs live in namespace sward::gpu and their sizes are
// static_assert'ed; in GLSL the same text declares std430 buffer elements. Every member is a 32-bit uint (or a
// vec4/uvec4), so std430 and C++ agree without padding rules; sub-fields are unpacked with the functions in
// plant_decode.glsl (GLSL) and vegetation/records.h (C++), which are the only places that know the bit layout.
//
// Coordinates: metres, right-handed, Z up. A plant is one point on the ground; the renderer expands it into
// billboard quads whose atlas cell is (row = category, column = variant).
#ifndef SWARD_PLANT_LAYOUT_H
#define SWARD_PLANT_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace sward::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = uint32_t;
#define SWARD_PLANT_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_PLANT_CONST(type, name, value) const type name = value
#endif

// Positions are quantised to 16 bits per axis over the field edge: step = fieldSize / kPlantPositionSteps
// (25 m fields: 0.38 mm). Decoding is origin + float(q) * step, exact for q * step and one rounding for the add.
SWARD_PLANT_CONST(uint, kPlantPositionSteps, 65536u);
// 2 category bits and 6 variant bits: at most 4 atlas rows and 64 atlas columns.
SWARD_PLANT_CONST(uint, kMaxPlantCategories, 4u);
SWARD_PLANT_CONST(uint, kMaxPlantVariants, 64u);
// Size byte s scales the category's base height by s / kPlantSizeDivisor (0 .. 1.99).
SWARD_PLANT_CONST(float, kPlantSizeDivisor, 128.0);
// Bend velocity snorm8 1.0 means this many plant heights per second.
SWARD_PLANT_CONST(float, kMaxBendVelocity, 4.0);
// PlantDynamic state byte.
SWARD_PLANT_CONST(uint, kPlantStateRest, 0u);       // untouched (inactive): bend may still hold wind-free rest pose
SWARD_PLANT_CONST(uint, kPlantStateRecovering, 1u); // bent by a collider, springing back
SWARD_PLANT_CONST(uint, kPlantStateFelled, 2u);     // flattened permanently (tyre tracks, squeezed grass)
SWARD_PLANT_CONST(uint, kPlantStateCut, 3u);        // cut at the cut-height fraction
// Cut height byte meaning "not cut".
SWARD_PLANT_CONST(uint, kPlantUncut, 255u);

// Immutable plant data, 16 bytes, written once when the field is generated.
struct PlantStatic {
    uint position;   // bits 0-15 x, bits 16-31 y: unsigned steps from the field's min corner (see above)
    uint height;     // float bits: world z of the plant base in metres, evaluated on the terrain at the
                     // *decoded* xy, so the decoded point lies exactly on the ground
    uint up;         // unit up vector, octahedral, 2 x snorm16 (bits 0-15 u, bits 16-31 v), error < 0.01 deg
    uint attributes; // bits 0-1 category (atlas row, 0..3); bits 2-7 variant (atlas column, 0..63);
                     // bits 8-15 orientation about up: angle = v * 2pi / 256 rad (1.4 deg steps);
                     // bits 16-23 random value v / 255 in [0, 1] (per-plant appearance variation);
                     // bits 24-31 size: plant height = category height * v / kPlantSizeDivisor (1..255)
};

// Interaction state, 8 bytes, read and written by the simulation every step.
struct PlantDynamic {
    uint bend;  // 2 x snorm16 (bits 0-15 x, bits 16-31 y): horizontal tip offset in plant heights, [-1, 1]
    uint state; // bits 0-9 / 10-19: bend velocity x / y, snorm10 times kMaxBendVelocity plant heights per
                // second (10 bits: a spring near rest still moves by more than half a quantum per tick);
                // bits 20-23: kPlantState*; bits 24-31: cut height as a fraction v / 255 of the plant height
                // (kPlantUncut = 255 means uncut). All snorm fields round half away from zero, on CPU and GPU.
};

// One 5x5 m plant cluster: culling box and the cluster's plants in its field's record arrays.
struct PlantCluster {
    vec4 boundsMin; // xyz world-space min corner, w unused. Conservative: every plant base +- its height on
                    // every axis, so any bend and any quad orientation of width <= 2 heights stays inside
    vec4 boundsMax; // xyz world-space max corner, w unused. An empty cluster (count 0) has min = max
    uvec4 range;    // x first plant (index into the field's records), y plant count, zw unused
};

// One 25x25 m grass field: decoding constants and where its records live in the tile's buffers.
struct PlantField {
    vec4 originStep; // xy world position of the field's min corner, z position step in metres, w unused
    uvec4 range;     // x first plant in the tile's record buffers, y plant count,
                     // z first cluster in the tile's cluster buffer, w cluster count
};

#ifdef __cplusplus
static_assert(sizeof(PlantStatic) == 16, "the issue caps static plant data at 16 bytes");
static_assert(sizeof(PlantDynamic) == 8, "the issue caps dynamic plant data at 8 bytes");
static_assert(sizeof(PlantCluster) == 48);
static_assert(sizeof(PlantField) == 32);
} // namespace sward::gpu
#endif
#undef SWARD_PLANT_CONST

#endif
