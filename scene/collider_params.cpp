#include "scene/collider_params.h"

#include "common/error.h"
#include "common/json_reader.h"

namespace sward {

RutParams parseRut(JsonReader& r, ColliderKind kind) {
    RutParams rut;
    rut.depth = r.numberF("rut_depth", 0.0f, 0.0, 1.0);
    rut.treadPitch = r.numberF("tread_pitch", 0.0f, 0.0, 10.0);
    rut.treadDepth = r.numberF("tread_depth", 0.0f, 0.0, 1.0);
    if (rut.depth > 0.0f && kind != ColliderKind::Push)
        r.fail(r.name("rut_depth") + " applies to push colliders only (wheels, feet, hulls)");
    if (rut.treadDepth > rut.depth) r.fail(r.name("tread_depth") + " must not exceed 'rut_depth'");
    if (rut.treadDepth > 0.0f && rut.treadPitch <= 0.0f)
        r.fail(r.name("tread_depth") + " needs a 'tread_pitch' above 0 (the metres between lugs)");
    return rut;
}

Collider parseColliderShape(JsonReader& r) {
    const auto shape = ColliderShape(r.choice("shape", 0, {"sphere", "capsule", "box"}));
    const auto kind = ColliderKind(r.choice("kind", 0, {"push", "gust", "downwash", "mower"}));
    const float radius = r.numberF("radius", 0.5f, 0.01, 100.0);
    const float force = r.numberF("force", 0.5f, 0.0, 1e6);
    // "length" is a downwash's reach below the path (default 2 m) or a capsule's segment length (default 1 m).
    const bool downwash = kind == ColliderKind::Downwash;
    const float length = r.numberF("length", downwash ? 2.0f : 1.0f, downwash ? 0.01 : 0.0, 1000.0);
    const glm::vec3 half(r.vector<3>("half_extents", glm::dvec3(0.5), 0.0, 1000.0));
    const float cutHeight = r.numberF("cut_height", 0.1f, 0.0, 10.0);
    const RutParams rut = parseRut(r, kind);
    if (downwash) return makeDownwash(0, glm::vec3(0.0f), radius, length, force);
    Collider collider;
    if (shape == ColliderShape::Sphere)
        collider = makeSphere(0, glm::vec3(0.0f), radius, force, kind);
    else if (shape == ColliderShape::Capsule)
        collider = makeCapsule(0, glm::vec3(-0.5f * length, 0, 0), glm::vec3(0.5f * length, 0, 0), radius, force, kind);
    else
        collider = makeBox(0, glm::vec3(0.0f), half, glm::mat3(1.0f), force, kind);
    collider.rut = rut;
    return kind == ColliderKind::Mower ? makeMower(collider, cutHeight) : collider;
}

std::vector<Collider> parsePlacedColliders(const nlohmann::json& colliders, const std::string& source) {
    require(colliders.is_array(), source + ": must be an array of colliders");
    require(colliders.size() <= kMaxPlacedColliders,
            source + ": at most " + std::to_string(kMaxPlacedColliders) + " colliders (got " +
                std::to_string(colliders.size()) + ")");
    std::vector<Collider> out;
    for (size_t i = 0; i < colliders.size(); ++i) {
        JsonReader r(colliders[i], source, "[" + std::to_string(i) + "]");
        const glm::vec3 centre(r.vector<3>("centre", glm::dvec3(0.0), -1e7, 1e7));
        r.required("centre", "the collider's world position");
        Collider c = parseColliderShape(r);
        r.finish();
        c.centre += centre;
        c.end += centre;
        c.id = kPlacedColliderBase + uint32_t(i);
        out.push_back(c);
    }
    return out;
}

} // namespace sward
