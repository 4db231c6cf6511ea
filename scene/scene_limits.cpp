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
