// Numbers the CPU and the GPU share that are not struct layouts (niagara's config.h): workgroup sizes, frames
// in flight, render pass variants and descriptor binding slots. One definition, two languages: in C++ the
// constants live in namespace sward::gpu; GLSL sees plain consts, valid in layout qualifiers
// (`layout(local_size_x = kComputeGroupSize)`, `layout(binding = kBindingFrame)`).
// Struct layouts are in gpu_layout.h (which includes this header). No glm here: the engine includes it too.
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
SWARD_CONST(uint, kPassTruth, 1u);  // ground truth: depth bits, labels, normals, one sample per pixel
SWARD_CONST(uint, kPassShadow, 2u); // sun shadow map: depth only, seen from the sun

// Descriptor binding slots of set 0 (push descriptors): the GLSL declarations and the C++ pipeline layouts and
// descriptor writes. A slot means something only within its pipeline layout: one group per layout.

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
SWARD_CONST(uint, kBindingCoverMap, 7u);         // the vegetation's far cover (terrain.frag), main pass only
SWARD_CONST(uint, kBindingGroundTextures, 8u);   // a mesh ground's base-colour textures (terrain.frag), main pass
SWARD_CONST(uint, kBindingMeshVertices, 2u);     // truth pass: a mesh's vertices, pulled by terrain_truth.vert
SWARD_CONST(uint, kBindingMeshIndices, 3u);      // (TerrainVertex[]) and object_truth.vert (ObjectVertex[]) / its
                                                 // triangle list (uint[]), so a vertex sees its whole triangle;
                                                 // rut patches' TerrainVertex[] and the patches in view (track.vert)
SWARD_CONST(uint, kBindingTrackTable, 9u);       // the blocks drawn as rut patches (ground_tracks.glsl)
SWARD_CONST(uint, kBindingFlowStatics, 10u);     // truth pass with flow: PlantStatic[] (plant.vert: a plant's size)
SWARD_CONST(uint, kBindingFlowDynamicsPrevious, 11u); // PlantDynamic[] at the previous tick
SWARD_CONST(uint, kBindingFlowDynamicsNext, 12u);     // PlantDynamic[] at the next tick
SWARD_CONST(uint, kBindingGroundMaterials, 13u); // the tile's ground material weights per category (terrain.frag,
                                                 // cover map texels; vegetation/cover_map.h), main pass only

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
SWARD_CONST(uint, kScanBindingCursor, 3u); // uint: first free instance of the frame's shared pool (tiles chain)
SWARD_CONST(uint, kScanBindingClusterOrder, 4u); // uint[clusters]: the order instances are laid out in (frontToBack)

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
