#include "scene/scene_limits.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/scene.h"

namespace sward {

void checkArrayLength(JsonReader& reader, const char* key, uint64_t limit, const char* why) {
    const nlohmann::json* array = reader.raw(key);
    if (array && array->is_array() && array->size() > limit)
        reader.fail(reader.name(key) + " has " + std::to_string(array->size()) + " entries, over the limit of " +
                    std::to_string(limit) + " (" + why + ")");
}

uint64_t estimatedRenderImageBytes(const RenderParams& render) {
    const uint64_t colour = 12 * uint64_t(render.samples); // RGBA16F + D32 per sample
    const uint64_t truth = 32 + (render.flow ? 32 : 0);    // depth bits, label and tile, normal (+ two flows)
    const uint64_t readback = 8 + truth;                   // resolved colour and the truth, on the host
    return uint64_t(render.width) * render.height * (colour + truth + readback);
}

void checkRenderResolution(const RenderParams& render, const std::string& source) {
    const uint64_t pixels = uint64_t(render.width) * render.height;
    require(pixels <= kMaxImagePixels, source + ": 'render.resolution' " + std::to_string(render.width) + "x" +
                                           std::to_string(render.height) + " is " + std::to_string(pixels) +
                                           " pixels (about " + std::to_string(estimatedRenderImageBytes(render) >> 20) +
                                           " MiB of render images), over the limit of " +
                                           std::to_string(kMaxImagePixels) + " (8192x8192)");
}

void checkSceneLimits(const Scene& scene) {
    uint64_t objectColliders = 0;
    for (const ObjectParams& object : scene.objects) objectColliders += object.colliders.size();
    const uint64_t perFrame = 4 * uint64_t(scene.actors.vehicles.size()) + scene.actors.colliders.size() +
                              scene.actors.gusts.count + objectColliders;
    const uint64_t records = perFrame * scene.sequence.frames;
    require(records <= kMaxColliderRecords,
            scene.source + ": 'sequence.frames' (" + std::to_string(scene.sequence.frames) + ") times " +
                std::to_string(perFrame) + " colliders per frame ('gusts.count' " +
                std::to_string(scene.actors.gusts.count) + ", 4 per vehicle, 'colliders', the objects' 'colliders') is " +
                std::to_string(records) + " collider records in frames.jsonl, over the limit of " +
                std::to_string(kMaxColliderRecords) + "; lower 'gusts.count' or 'sequence.frames'");
}

} // namespace sward
