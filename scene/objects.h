// Scene objects: glTF models (e.g. the default rover, examples/assets/rover.gltf) that drive along a path on
// the terrain, are drawn, cast shadows, appear in the ground truth (semantic class 8, instance 16,000,000 + k)
// and carry colliders attached to their nodes by name (a wheel's capsule turns and climbs with the wheel).
//
// Frames: a model is read in sward's Z-up convention (gltf_mesh.h): glTF's front (+Z) becomes the model's -y,
// its left (+X) stays +x, its top (+Y) becomes +z. The model's origin is the point that rests on the ground.
// An object's pose is a pure function of simulation time (like every path in sward), so any frame of a sequence
// can be computed on its own (shards, resume).
#pragma once

#include "interaction/colliders.h"
#include "world/gltf_mesh.h"
#include "world/path.h"

#include "shared/object_layout.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sward {

class Ground;
class JsonReader;

// A collider attached to a node of the object's model. Sizes and offsets are metres in the node's frame
// (Z-up), multiplied by the object's scale.
struct ObjectColliderParams {
    std::string node; // node name in the model
    ColliderShape shape = ColliderShape::Sphere;
    ColliderKind kind = ColliderKind::Push;
    float radius = 0.5f;         // sphere, capsule, downwash
    float length = 0.0f;         // capsule: segment length along `axis`; downwash: reach below the node
    int axis = 0;                // capsule axis in the node frame: 0 x, 1 y, 2 z
    glm::vec3 halfExtents{0.5f}; // box, along the node's axes
    glm::vec3 offset{0.0f};      // collider centre in the node frame
    float force = 0.5f;          // push strength; above a category's fell force the plants stay flat
    float cutHeight = 0.1f;      // mower: metres above the plant base
    RutParams rut;               // push: the ruts it leaves in the ground (none by default)
};

struct ObjectParams {
    std::string name;           // "object<k>" when not given
    std::string model;          // path of the .gltf / .glb file, resolved against the scene's folder
    AssetPolicy assets;         // the scene's: where the model and the buffer files it names may be read from
    double scale = 1.0;         // uniform scale of the model
    double yawDegrees = 0.0;    // extra turn of the model about its up axis (counter-clockwise seen from above)
    bool alignToTerrain = true; // pitch and roll with the terrain under the model's footprint
    PathParams path;            // where the model's origin goes; heading = direction of travel
    std::vector<ObjectColliderParams> colliders;
};

// Limits that keep collider ids unique (objectColliders).
inline constexpr size_t kMaxObjects = 10000;
inline constexpr size_t kMaxCollidersPerObject = 100;

// Instance id (as in the instance images: 16,000,000 + k, below 2^24 and exact in float32) and truth label
// ((semantic class 8 << 24) | instance id) of object k.
inline uint32_t objectInstanceId(size_t k) {
    return gpu::kInstanceObjectBase + uint32_t(k);
}
inline uint32_t objectLabel(size_t k) {
    return gpu::kSemanticObject << gpu::kInstanceBits | objectInstanceId(k);
}

// Reads the "objects" array (absent: none) of the scene object `scene`. Model paths are resolved against
// `sceneDir` (empty: as they are) and checked against `assets`. Errors name the file and the JSON path, e.g.
// "scene.json: 'objects[0].colliders[1].radius' must be ...". Does not open the model files (loadObjectModels does).
std::vector<ObjectParams> parseObjects(JsonReader& scene, const std::string& sceneDir, const AssetPolicy& assets = {});

// Loads every object's model (its buffer files checked against the object's `assets`) and checks that each collider
// names a node of it; errors name `source` and the JSON path of the offending value. Models are returned in object
// order.
std::vector<ObjectModel> loadObjectModels(const std::vector<ObjectParams>& objects, const std::string& source);

struct ObjectPose {
    glm::dmat4 worldFromModel{1.0};                          // includes the scale
    glm::dvec3 position{0.0};                                // world position of the model origin
    glm::dvec3 forward{1, 0, 0}, left{0, 1, 0}, up{0, 0, 1}; // unit world axes of the object (travel frame)
    double distance = 0.0;                                   // metres travelled along the path
};

// The object's pose at simulation time `time`: origin on the path at the terrain height (plus the path's
// height_above_ground), model front (-y) along the direction of travel; with alignToTerrain its up axis is the
// normal of the plane fitted to the terrain heights under the four corners of the model's footprint (and the
// origin sits on that plane), else world +z.
ObjectPose objectPose(const ObjectParams& object, const ObjectModel& model, const Ground& terrain, double time);
// World-from-node transform of the node named `node` at time `time`; throws sward::Error if there is none.
glm::dmat4 objectNodeToWorld(const ObjectParams& object, const ObjectModel& model, const std::string& node,
                             const Ground& terrain, double time);
// World-from-node transforms of every node of the model (ObjectModel::nodes order).
std::vector<glm::dmat4> objectNodeTransforms(const ObjectParams& object, const ObjectModel& model,
                                             const Ground& terrain, double time);

// Every object collider at time `time`, object by object, collider by collider, with the stable id
// 200000 + 100 * object + collider. `models` as returned by loadObjectModels. Append these to actorColliders().
std::vector<Collider> objectColliders(const std::vector<ObjectParams>& objects, const std::vector<ObjectModel>& models,
                                      const Ground& terrain, double time);
// Object k's colliders alone, with the same ids: an object of a world stands on its own ground (world_objects.h).
std::vector<Collider> objectColliders(const ObjectParams& object, const ObjectModel& model, size_t k,
                                      const Ground& terrain, double time);

} // namespace sward
