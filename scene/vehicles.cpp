#include "scene/vehicles.h"

#include "common/error.h"
#include "world/heightfield.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace sward {

std::vector<WheelPose> vehicleWheels(const VehicleParams& v, const Heightfield& terrain, double time) {
    PathPose pose = pathPose(v.path, terrain, time);
    return vehicleWheelsAt(v, terrain, glm::dvec2(pose.position), pose.heading);
}

std::vector<WheelPose> vehicleWheelsAt(const VehicleParams& v, const Heightfield& terrain, glm::dvec2 position,
                                       glm::dvec2 heading) {
    glm::dvec2 forward = heading, left(-forward.y, forward.x);
    std::vector<WheelPose> wheels;
    for (int w = 0; w < 4; ++w) {
        double along = (w < 2 ? 0.5 : -0.5) * v.wheelBase, across = (w % 2 == 0 ? 0.5 : -0.5) * v.trackWidth;
        glm::dvec2 xy = position + forward * along + left * across;
        double ground = terrain.height(glm::vec2(xy));
        wheels.push_back({glm::vec3(glm::dvec3(xy, ground + v.wheelRadius - v.sink)), glm::vec3(glm::dvec3(left, 0.0))});
    }
    return wheels;
}

std::vector<Collider> wheelColliders(const VehicleParams& vehicle, const std::vector<WheelPose>& wheels, uint32_t index) {
    std::vector<Collider> colliders;
    for (uint32_t w = 0; w < wheels.size(); ++w) {
        // A wheel is a capsule along its axle: radius = wheel radius, length = wheel width.
        glm::vec3 half = wheels[w].axle * (0.5f * std::max(vehicle.wheelWidth - 2.0f * vehicle.wheelRadius, 0.0f));
        colliders.push_back(makeCapsule(uint32_t(1000 * (index + 1) + w), wheels[w].centre - half,
                                        wheels[w].centre + half, vehicle.wheelRadius, vehicle.weight));
    }
    return colliders;
}

std::vector<Collider> actorColliders(const ActorParams& actors, const Heightfield& terrain, double time, uint64_t tick,
                                     float timeStep) {
    std::vector<Collider> colliders;
    for (size_t v = 0; v < actors.vehicles.size(); ++v) {
        auto wheels = wheelColliders(actors.vehicles[v], vehicleWheels(actors.vehicles[v], terrain, time), uint32_t(v));
        colliders.insert(colliders.end(), wheels.begin(), wheels.end());
    }
    for (size_t i = 0; i < actors.colliders.size(); ++i) {
        const MovingColliderParams& m = actors.colliders[i];
        Collider c = m.collider;
        glm::vec3 position(pathPose(m.path, terrain, time).position);
        glm::vec3 offset = position - c.centre;
        c.centre += offset;
        c.end += offset;
        c.id = uint32_t(100000 + i);
        colliders.push_back(c);
    }
    if (actors.gusts.count > 0) {
        glm::vec2 lo = terrain.origin(), hi = lo + terrain.extent();
        Aabb area{glm::vec3(lo, terrain.minHeight()), glm::vec3(hi, terrain.maxHeight() + actors.gusts.height)};
        auto gusts = makeGusts(actors.gusts.seed, actors.gusts.count, area, tick, timeStep);
        colliders.insert(colliders.end(), gusts.begin(), gusts.end());
    }
    return colliders;
}

namespace {

float number(const nlohmann::json& j, const char* key, float value, float lo, float hi, const std::string& where) {
    if (!j.contains(key)) return value;
    const nlohmann::json& v = j.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo || v.get<double>() > hi)
        throw Error(where + "." + key + " must be a number between " + std::to_string(lo) + " and " + std::to_string(hi));
    return v.get<float>();
}

void onlyKeys(const nlohmann::json& j, std::initializer_list<const char*> keys, const std::string& where) {
    if (!j.is_object()) throw Error(where + " must be an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (const char* k : keys) known = known || it.key() == k;
        if (!known) throw Error(where + ": unknown key '" + it.key() + "'");
    }
}

} // namespace

ActorParams parseActors(const nlohmann::json* vehicles, const nlohmann::json* colliders, const nlohmann::json* gusts,
                        const std::string& source) {
    ActorParams actors;
    if (vehicles) {
        if (!vehicles->is_array()) throw Error(source + ": 'vehicles' must be an array");
        for (size_t i = 0; i < vehicles->size(); ++i) {
            const nlohmann::json& j = (*vehicles)[i];
            std::string where = source + ": 'vehicles[" + std::to_string(i) + "]'";
            onlyKeys(j, {"name", "path", "wheel_base", "track_width", "wheel_radius", "wheel_width", "weight", "sink"}, where);
            VehicleParams v;
            if (j.contains("name")) v.name = j.at("name").is_string() ? j.at("name").get<std::string>() : v.name;
            if (!j.contains("path")) throw Error(where + " needs a 'path'");
            v.path = parsePath(j.at("path"), where + ".path");
            v.wheelBase = number(j, "wheel_base", v.wheelBase, 0.05f, 20.0f, where);
            v.trackWidth = number(j, "track_width", v.trackWidth, 0.05f, 20.0f, where);
            v.wheelRadius = number(j, "wheel_radius", v.wheelRadius, 0.01f, 5.0f, where);
            v.wheelWidth = number(j, "wheel_width", v.wheelWidth, 0.01f, 5.0f, where);
            v.weight = number(j, "weight", v.weight, 0.0f, 1e6f, where);
            v.sink = number(j, "sink", v.sink, 0.0f, 1.0f, where);
            actors.vehicles.push_back(v);
        }
    }
    if (colliders) {
        if (!colliders->is_array()) throw Error(source + ": 'colliders' must be an array");
        for (size_t i = 0; i < colliders->size(); ++i) {
            const nlohmann::json& j = (*colliders)[i];
            std::string where = source + ": 'colliders[" + std::to_string(i) + "]'";
            onlyKeys(j, {"shape", "kind", "radius", "length", "half_extents", "force", "cut_height", "path"}, where);
            for (const char* key : {"shape", "kind"})
                if (j.contains(key) && !j.at(key).is_string()) throw Error(where + "." + key + " must be a string");
            std::string shape = j.value("shape", "sphere"), kind = j.value("kind", "push");
            if (!j.contains("path")) throw Error(where + " needs a 'path'");
            MovingColliderParams m;
            m.path = parsePath(j.at("path"), where + ".path");
            float radius = number(j, "radius", 0.5f, 0.01f, 100.0f, where);
            float force = number(j, "force", 0.5f, 0.0f, 1e6f, where);
            if (kind == "downwash") {
                float reach = number(j, "length", 2.0f, 0.01f, 1000.0f, where);
                m.collider = makeDownwash(0, glm::vec3(0.0f), radius, reach, force);
            } else {
                ColliderKind k = kind == "push" ? ColliderKind::Push : kind == "gust" ? ColliderKind::Gust
                                 : kind == "mower" ? ColliderKind::Mower
                                                   : throw Error(where + ".kind must be push, gust, downwash or mower");
                if (shape == "sphere") m.collider = makeSphere(0, glm::vec3(0.0f), radius, force, k);
                else if (shape == "capsule") {
                    float length = number(j, "length", 1.0f, 0.0f, 1000.0f, where);
                    m.collider = makeCapsule(0, glm::vec3(-0.5f * length, 0, 0), glm::vec3(0.5f * length, 0, 0), radius, force, k);
                } else if (shape == "box") {
                    glm::vec3 half(0.5f);
                    if (j.contains("half_extents")) {
                        const auto& h = j.at("half_extents");
                        if (!h.is_array() || h.size() != 3) throw Error(where + ".half_extents must be [x, y, z]");
                        half = glm::vec3(h[0].get<float>(), h[1].get<float>(), h[2].get<float>());
                    }
                    m.collider = makeBox(0, glm::vec3(0.0f), half, glm::mat3(1.0f), force, k);
                } else {
                    throw Error(where + ".shape must be sphere, capsule or box");
                }
                if (k == ColliderKind::Mower) m.collider = makeMower(m.collider, number(j, "cut_height", 0.1f, 0.0f, 10.0f, where));
            }
            actors.colliders.push_back(m);
        }
    }
    if (gusts) {
        std::string where = source + ": 'gusts'";
        onlyKeys(*gusts, {"count", "seed", "height"}, where);
        // Whole numbers, read exactly (a float would round seeds above 2^24).
        for (const char* key : {"count", "seed"})
            if (gusts->contains(key) && !gusts->at(key).is_number_unsigned())
                throw Error(where + "." + key + " must be a non-negative integer");
        actors.gusts.count = gusts->value("count", 0u);
        if (actors.gusts.count > 100000) throw Error(where + ".count must be at most 100000");
        actors.gusts.seed = gusts->value("seed", uint64_t(1));
        actors.gusts.height = number(*gusts, "height", actors.gusts.height, 0.0f, 1000.0f, where);
    }
    return actors;
}

} // namespace sward
