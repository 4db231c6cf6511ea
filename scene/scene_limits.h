// Limits on the counts of a scene file that scale memory, time or id spaces (docs/scene-format.md, "Limits").
// Each is checked while parsing, before anything is built, so an absurd scene gets one error naming the key instead
// of std::bad_alloc, an hour of work or ground truth whose ids wrap.
#pragma once

#include "shared/gpu_layout.h"

#include <cstdint>
#include <string>

namespace sward {

class JsonReader;
struct RenderParams;
struct Scene;

// "objects": each object is one ground-truth instance id (gpu::kMaxObjectInstances would be the hard bound), a
// model to load and a name compared with every other; 10,000 keeps parsing and loading within seconds.
inline constexpr uint32_t kMaxSceneObjects = 10000;
static_assert(kMaxSceneObjects <= gpu::kMaxObjectInstances, "object ids must stay within the instance-id space");
// "vehicles": wheel collider ids 1000 * (v + 1) + w must stay below the free colliders' 100000.
inline constexpr uint32_t kMaxVehicles = 99;
// "colliders": ids 100000 + i must stay below the objects' colliders at 200000.
inline constexpr uint32_t kMaxFreeColliders = 100000;
// frames.jsonl lists every collider of every frame of the sequence (a few hundred bytes each, held in memory
// while it is written): 'sequence.frames' times the colliders per frame is bounded.
inline constexpr uint64_t kMaxColliderRecords = 2000000;

// Estimated bytes of one camera's render images at the scene's 'render' settings: the multisampled colour and
// depth targets (RGBA16F + D32 per sample), the ground-truth targets (depth bits, label and tile, normal: 32 bytes,
// and 32 more with flow) and their host readback copies. Stated in the refusal of 'render.resolution'.
uint64_t estimatedRenderImageBytes(const RenderParams& render);
// Throws "<source>: 'render.resolution' WxH is N pixels (about M MiB of render images), over the limit of
// kMaxImagePixels (8192x8192)": a scene asks for what the command line may (16384x16384 reached
// VK_ERROR_OUT_OF_DEVICE_MEMORY).
void checkRenderResolution(const RenderParams& render, const std::string& source);

// Throws "<source>: '<key>' has N entries, over the limit of M (<why>)" when the array under `key` is longer than
// `limit`; checked before its elements are parsed.
void checkArrayLength(JsonReader& reader, const char* key, uint64_t limit, const char* why);

// Checks the parsed scene's cross-key limits (kMaxColliderRecords); throws sward::Error naming the keys.
void checkSceneLimits(const Scene& scene);

} // namespace sward
