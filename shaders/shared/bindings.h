// Descriptor binding slots of set 0 (push descriptors), shared by the GLSL declarations and the C++ pipeline
// layouts and descriptor writes. A slot means something only within its pipeline layout: one group per layout.
// In C++ the constants live in namespace sward::gpu.
#ifndef SWARD_BINDINGS_H
#define SWARD_BINDINGS_H

#ifdef __cplusplus
#include <cstdint>
namespace sward::gpu {
using uint = uint32_t;
#define SWARD_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_CONST(type, name, value) const type name = value
#endif

// Scene draws (terrain, sky, objects, plants) and the plant bake.
SWARD_CONST(uint, kBindingFrame, 0u);            // FrameConstants (frame.glsl)
SWARD_CONST(uint, kBindingVegetation, 1u);       // VegetationConstants (vegetation.glsl; the expansion's too)
SWARD_CONST(uint, kBindingObjectTransforms, 1u); // ObjectTransform[] (object.vert; objects have no vegetation)
SWARD_CONST(uint, kBindingPlantInstances, 2u);   // ExpandedPlant[] (plant.vert, plant_bake.comp input), or the
                                                 // BakedVertex[] that replace them (plant_static.vert)
SWARD_CONST(uint, kBindingAtlasCells, 3u);       // AtlasCellGpu[] (plant_vertex.glsl)
SWARD_CONST(uint, kBindingAtlas, 4u);            // atlas texture (plant_fragment.glsl)
SWARD_CONST(uint, kBindingShadowMap, 5u);        // sun shadow map (shadow.glsl), main pass only
SWARD_CONST(uint, kBindingInstancePlants, 6u);   // plant index per instance (plant.vert, ground-truth ids)
SWARD_CONST(uint, kBindingBakedVertices, 4u);    // BakedVertex[] written by plant_bake.comp (it has no atlas)

// Vegetation expansion (vegetation_expand.comp), besides its constants at kBindingVegetation.
SWARD_CONST(uint, kExpandBindingStatics, 0u);
SWARD_CONST(uint, kExpandBindingDynamics, 2u);
SWARD_CONST(uint, kExpandBindingClusters, 3u);
SWARD_CONST(uint, kExpandBindingFields, 4u);
SWARD_CONST(uint, kExpandBindingClusterCounts, 5u);
SWARD_CONST(uint, kExpandBindingInstances, 6u);
SWARD_CONST(uint, kExpandBindingInstancePlants, 7u);

// Expansion prefix sum (vegetation_scan.comp).
SWARD_CONST(uint, kScanBindingClusterCounts, 0u);
SWARD_CONST(uint, kScanBindingDraws, 1u);
SWARD_CONST(uint, kScanBindingStats, 2u);

// Interaction recovery (plant_recovery.comp).
SWARD_CONST(uint, kRecoveryBindingDynamics, 0u);
SWARD_CONST(uint, kRecoveryBindingContacts, 1u);
SWARD_CONST(uint, kRecoveryBindingActiveFields, 2u);

// sward-view present pass (present.frag): the resolved HDR image.
SWARD_CONST(uint, kPresentBindingImage, 0u);

// Engine self-test (test_roundtrip.comp).
SWARD_CONST(uint, kTestBindingInput, 0u);
SWARD_CONST(uint, kTestBindingOutput, 1u);

#ifdef __cplusplus
} // namespace sward::gpu
#endif
#undef SWARD_CONST

#endif
