#include "scene/objects.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/collider_params.h"
#include "world/ground.h"

#include <cmath>
#include <numbers>

namespace sward {

namespace {

// A string that names something (a node, a model file, an object): present means non-empty.
std::string nonEmptyString(JsonReader& r, const char* key, std::string value) {
    value = r.string(key, std::move(value));
    if (value.empty()) r.fail(r.name(key) + " must be a non-empty string");
    return value;
}

ObjectColliderParams parseCollider(JsonReader r) {
    ObjectColliderParams c;
    r.required("node", "the name of a node of the model");
    c.node = nonEmptyString(r, "node", "");
    c.shape = ColliderShape(r.choice("shape", 0, {"sphere", "capsule", "box"}));
    c.kind = ColliderKind(r.choice("kind", 0, {"push", "gust", "downwash", "mower"}));
    c.radius = r.numberF("radius", c.radius, 0.001, 100.0);
    c.length = r.numberF("length", c.kind == ColliderKind::Downwash ? 2.0f : 0.0f, 0.0, 1000.0);
    if (c.kind == ColliderKind::Downwash && c.length <= 0.0f)
        r.fail(r.name("length") + " must be above 0 for a downwash");
    c.axis = r.choice("axis", 0, {"x", "y", "z"});
    c.halfExtents = glm::vec3(r.vector<3>("half_extents", glm::dvec3(c.halfExtents), 0.001, 100.0));
    c.offset = glm::vec3(r.vector<3>("offset", glm::dvec3(c.offset), -1000.0, 1000.0));
    c.force = r.numberF("force", c.force, 0.0, 1e6);
    c.cutHeight = r.numberF("cut_height", c.cutHeight, 0.0, 10.0);
    c.rut = parseRut(r, c.kind);
    r.finish();
    return c;
}

ObjectParams parseObject(JsonReader r, size_t k, const std::vector<ObjectParams>& before, const std::string& sceneDir,
                         const AssetPolicy& assets) {
    ObjectParams o;
    o.name = nonEmptyString(r, "name", "object" + std::to_string(k));
    for (size_t j = 0; j < before.size(); ++j) // camera rigs mount on objects by name
        if (before[j].name == o.name)
            r.fail(r.name("name") + " '" + o.name + "' is already the name of objects[" + std::to_string(j) + "]");
    r.required("model", "a .gltf or .glb file");
    o.model = assets.resolve(nonEmptyString(r, "model", ""), sceneDir, r.source() + ": " + r.name("model"));
    o.assets = assets;
    o.scale = r.number("scale", o.scale, 0.001, 1000.0);
    o.yawDegrees = r.number("yaw_deg", o.yawDegrees, -360.0, 360.0);
    o.alignToTerrain = r.boolean("align_to_terrain", o.alignToTerrain);
    o.path =
        parsePath(r.required("path", "{\"points\": [[x, y], ...], \"speed\": ...}"), r.source(), r.childPath("path"));
    std::vector<JsonReader> colliders = r.objects("colliders");
    if (colliders.size() > kMaxCollidersPerObject)
        r.fail(r.name("colliders") + " has more than " + std::to_string(kMaxCollidersPerObject) + " entries");
    for (JsonReader& collider : colliders) o.colliders.push_back(parseCollider(collider));
    r.finish();
    return o;
}

// The object's footprint in its travel frame: signed extents along forward (front, rear) and left (left, right).
struct Footprint {
    double front, rear, left, right;
};

Footprint footprint(const ObjectParams& object, const ObjectModel& model) {
    const double yaw = object.yawDegrees * std::numbers::pi / 180.0, c = std::cos(yaw), s = std::sin(yaw);
    Footprint f{-1e300, 1e300, -1e300, 1e300};
    for (int corner = 0; corner < 4; ++corner) {
        glm::dvec2 p(corner & 1 ? model.boundsMax.x : model.boundsMin.x,
                     corner & 2 ? model.boundsMax.y : model.boundsMin.y);
        glm::dvec2 turned(c * p.x - s * p.y, s * p.x + c * p.y);
        double forward = -turned.y * object.scale, left = turned.x * object.scale; // model front is -y, left +x
        f.front = std::max(f.front, forward);
        f.rear = std::min(f.rear, forward);
        f.left = std::max(f.left, left);
        f.right = std::min(f.right, left);
    }
    return f;
}

const ObjectModel& modelOf(const std::vector<ObjectModel>& models, size_t k) {
    require(k < models.size(), "object " + std::to_string(k) + " has no loaded model");
    return models[k];
}

} // namespace

std::vector<ObjectParams> parseObjects(JsonReader& scene, const std::string& sceneDir, const AssetPolicy& assets) {
    std::vector<JsonReader> objects = scene.objects("objects");
    if (objects.size() > kMaxObjects)
        scene.fail(scene.name("objects") + " has " + std::to_string(objects.size()) + " entries, at most " +
                   std::to_string(kMaxObjects) + " are supported");
    std::vector<ObjectParams> result;
    for (size_t k = 0; k < objects.size(); ++k) result.push_back(parseObject(objects[k], k, result, sceneDir, assets));
    return result;
}

std::vector<ObjectModel> loadObjectModels(const std::vector<ObjectParams>& objects, const std::string& source) {
    std::vector<ObjectModel> models;
    for (size_t k = 0; k < objects.size(); ++k) {
        const std::string where = source + ": 'objects[" + std::to_string(k) + "]";
        try {
            models.push_back(loadGltfModel(objects[k].model, objects[k].assets));
        } catch (const Error& e) {
            throw Error(where + ".model': " + e.what());
        }
        const ObjectModel& model = models.back();
        for (size_t c = 0; c < objects[k].colliders.size(); ++c) {
            const std::string& node = objects[k].colliders[c].node;
            if (model.findNode(node) >= 0) continue;
            std::string names;
            for (const ModelNode& n : model.nodes)
                if (!n.name.empty()) names += (names.empty() ? "" : ", ") + n.name;
            throw Error(where + ".colliders[" + std::to_string(c) + "].node': model '" + objects[k].model +
                        "' has no node named '" + node + "' (its nodes: " + (names.empty() ? "none named" : names) +
                        ")");
        }
    }
    return models;
}

ObjectPose objectPose(const ObjectParams& object, const ObjectModel& model, const Ground& terrain, double time) {
    const PathPose travel = pathPose(object.path, terrain, time);
    ObjectPose pose;
    pose.distance = travel.distance;
    pose.position = travel.position;
    glm::dvec3 forward(travel.heading, 0.0), left(-travel.heading.y, travel.heading.x, 0.0), up(0.0, 0.0, 1.0);
    if (object.alignToTerrain) {
        // Fit a plane to the terrain under the footprint's corners: its slopes along forward and left tilt the
        // object, its height at the origin carries it (four wheels on a bump straddle it, as real ones do).
        const Footprint f = footprint(object, model);
        const glm::dvec2 origin(travel.position);
        auto h = [&](double along, double across) {
            glm::dvec2 xy = origin + glm::dvec2(forward) * along + glm::dvec2(left) * across;
            return double(terrain.height(glm::vec2(xy)));
        };
        const double fl = h(f.front, f.left), fr = h(f.front, f.right), rl = h(f.rear, f.left), rr = h(f.rear, f.right);
        const double length = f.front - f.rear, width = f.left - f.right;
        const double slopeForward = length > 1e-9 ? ((fl + fr) - (rl + rr)) / (2.0 * length) : 0.0;
        const double slopeLeft = width > 1e-9 ? ((fl + rl) - (fr + rr)) / (2.0 * width) : 0.0;
        const double mean = 0.25 * (fl + fr + rl + rr);
        const double atOrigin = mean - slopeForward * 0.5 * (f.front + f.rear) - slopeLeft * 0.5 * (f.left + f.right);
        pose.position.z = atOrigin + object.path.heightAboveGround;
        forward = glm::normalize(forward + glm::dvec3(0.0, 0.0, slopeForward));
        const glm::dvec3 tiltedLeft = glm::normalize(left + glm::dvec3(0.0, 0.0, slopeLeft));
        up = glm::normalize(glm::cross(forward, tiltedLeft));
        left = glm::cross(up, forward);
    }
    pose.forward = forward;
    pose.left = left;
    pose.up = up;
    // Model axes: x -> left, y -> back (the glTF front, +Z, became -y), z -> up; then the yaw and the scale.
    glm::dmat4 frame(glm::dvec4(left, 0.0), glm::dvec4(-forward, 0.0), glm::dvec4(up, 0.0),
                     glm::dvec4(pose.position, 1.0));
    const double yaw = object.yawDegrees * std::numbers::pi / 180.0, c = std::cos(yaw), s = std::sin(yaw);
    glm::dmat4 turn(glm::dvec4(c, s, 0, 0), glm::dvec4(-s, c, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 0, 1));
    glm::dmat4 scale(object.scale);
    scale[3][3] = 1.0;
    pose.worldFromModel = frame * turn * scale;
    return pose;
}

glm::dmat4 objectNodeToWorld(const ObjectParams& object, const ObjectModel& model, const std::string& node,
                             const Ground& terrain, double time) {
    const int index = model.findNode(node);
    require(index >= 0, "object '" + object.name + "': model '" + model.path + "' has no node named '" + node + "'");
    return objectPose(object, model, terrain, time).worldFromModel * model.nodes[size_t(index)].modelFromNode;
}

std::vector<glm::dmat4> objectNodeTransforms(const ObjectParams& object, const ObjectModel& model,
                                             const Ground& terrain, double time) {
    const glm::dmat4 world = objectPose(object, model, terrain, time).worldFromModel;
    std::vector<glm::dmat4> transforms;
    transforms.reserve(model.nodes.size());
    for (const ModelNode& node : model.nodes) transforms.push_back(world * node.modelFromNode);
    return transforms;
}

std::vector<Collider> objectColliders(const std::vector<ObjectParams>& objects, const std::vector<ObjectModel>& models,
                                      const Ground& terrain, double time) {
    std::vector<Collider> colliders;
    for (size_t k = 0; k < objects.size(); ++k) {
        if (objects[k].colliders.empty()) continue;
        const std::vector<Collider> own = objectColliders(objects[k], modelOf(models, k), k, terrain, time);
        colliders.insert(colliders.end(), own.begin(), own.end());
    }
    return colliders;
}

std::vector<Collider> objectColliders(const ObjectParams& object, const ObjectModel& model, size_t k,
                                      const Ground& terrain, double time) {
    std::vector<Collider> colliders;
    if (object.colliders.empty()) return colliders;
    const glm::dmat4 world = objectPose(object, model, terrain, time).worldFromModel;
    const float scale = float(object.scale);
    for (size_t i = 0; i < object.colliders.size(); ++i) {
        const ObjectColliderParams& p = object.colliders[i];
        const int node = model.findNode(p.node);
        require(node >= 0,
                "object '" + object.name + "': model '" + model.path + "' has no node named '" + p.node + "'");
        const glm::dmat4 toWorld = world * model.nodes[size_t(node)].modelFromNode;
        auto at = [&](glm::dvec3 local) { return glm::vec3(glm::dvec3(toWorld * glm::dvec4(local, 1.0))); };
        const uint32_t id = uint32_t(200000 + 100 * k + i);
        const glm::dvec3 centre(p.offset);
        Collider c;
        if (p.kind == ColliderKind::Downwash) {
            c = makeDownwash(id, at(centre), p.radius * scale, p.length * scale, p.force);
        } else {
            if (p.shape == ColliderShape::Sphere) {
                c = makeSphere(id, at(centre), p.radius * scale, p.force, p.kind);
            } else if (p.shape == ColliderShape::Capsule) {
                // Sizes ignore node scales (only the object's scale applies): the axis direction is unit.
                glm::vec3 half = glm::vec3(glm::normalize(glm::dvec3(toWorld[p.axis]))) * (0.5f * p.length * scale);
                glm::vec3 middle = at(centre);
                c = makeCapsule(id, middle - half, middle + half, p.radius * scale, p.force, p.kind);
            } else {
                // The node's axes in world space, scale and any shear removed (Gram-Schmidt).
                glm::dvec3 x = glm::normalize(glm::dvec3(toWorld[0]));
                glm::dvec3 y = glm::normalize(glm::dvec3(toWorld[1]) - x * glm::dot(x, glm::dvec3(toWorld[1])));
                // A box is symmetric, so a mirrored node's box is the same box in a right-handed frame.
                glm::dvec3 z = glm::cross(x, y);
                c = makeBox(id, at(centre), p.halfExtents * scale, glm::mat3(glm::dmat3(x, y, z)), p.force, p.kind);
            }
            if (p.kind == ColliderKind::Mower) c = makeMower(c, p.cutHeight);
            c.rut = p.rut;
        }
        colliders.push_back(c);
    }
    return colliders;
}

} // namespace sward
