#include "scene/vehicles.h"

#include "scene/collider_params.h"

#include "common/json_reader.h"
#include "scene/scene_limits.h"
#include "world/ground.h"

#include <cmath>

namespace sward {

std::vector<WheelPose> vehicleWheels(const VehicleParams& v, const Ground& terrain, double time) {
    PathPose pose = pathPose(v.path, terrain, time);
    return vehicleWheelsAt(v, terrain, glm::dvec2(pose.position), pose.heading);
}

std::vector<WheelPose> vehicleWheelsAt(const VehicleParams& v, const Ground& terrain, glm::dvec2 position,
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
        colliders.back().rut = vehicle.rut;
    }
    return colliders;
}

Collider movingCollider(const MovingColliderParams& m, uint32_t index, const Ground& terrain, double time) {
    Collider c = m.collider;
    const glm::vec3 offset = glm::vec3(pathPose(m.path, terrain, time).position) - c.centre;
    c.centre += offset;
    c.end += offset;
    c.id = uint32_t(100000 + index);
    return c;
}

std::vector<Collider> actorColliders(const ActorParams& actors, const Ground& terrain, double time, uint64_t tick,
                                     float timeStep) {
    std::vector<Collider> colliders;
    for (size_t v = 0; v < actors.vehicles.size(); ++v) {
        auto wheels = wheelColliders(actors.vehicles[v], vehicleWheels(actors.vehicles[v], terrain, time), uint32_t(v));
        colliders.insert(colliders.end(), wheels.begin(), wheels.end());
    }
    for (size_t i = 0; i < actors.colliders.size(); ++i)
        colliders.push_back(movingCollider(actors.colliders[i], uint32_t(i), terrain, time));
    if (actors.gusts.count > 0) {
        glm::vec2 lo = terrain.boundsMin(), hi = terrain.boundsMax();
        Aabb area{glm::vec3(lo, terrain.minHeight()), glm::vec3(hi, terrain.maxHeight() + actors.gusts.height)};
        auto gusts = makeGusts(actors.gusts.seed, actors.gusts.count, area, tick, timeStep);
        colliders.insert(colliders.end(), gusts.begin(), gusts.end());
    }
    return colliders;
}

namespace {

VehicleParams parseVehicle(JsonReader r) {
    VehicleParams v;
    v.name = r.string("name", v.name);
    v.path = parsePath(r.required("path", "the vehicle centre's path"), r.source(), r.childPath("path"));
    v.wheelBase = r.numberF("wheel_base", v.wheelBase, 0.05, 20.0);
    v.trackWidth = r.numberF("track_width", v.trackWidth, 0.05, 20.0);
    v.wheelRadius = r.numberF("wheel_radius", v.wheelRadius, 0.01, 5.0);
    v.wheelWidth = r.numberF("wheel_width", v.wheelWidth, 0.01, 5.0);
    v.weight = r.numberF("weight", v.weight, 0.0, 1e6);
    v.sink = r.numberF("sink", v.sink, 0.0, 1.0);
    v.rut = parseRut(r, ColliderKind::Push);
    r.finish();
    return v;
}

MovingColliderParams parseMovingCollider(JsonReader r) {
    MovingColliderParams m;
    m.collider = parseColliderShape(r);
    m.path = parsePath(r.required("path", "the collider's path"), r.source(), r.childPath("path"));
    r.finish();
    return m;
}

} // namespace

ActorParams parseActors(JsonReader& scene, uint64_t gustSeed) {
    ActorParams actors;
    checkArrayLength(scene, "vehicles", kMaxVehicles, "the wheel collider ids");
    checkArrayLength(scene, "colliders", kMaxFreeColliders, "the collider ids");
    for (JsonReader& vehicle : scene.objects("vehicles")) actors.vehicles.push_back(parseVehicle(vehicle));
    for (JsonReader& collider : scene.objects("colliders")) actors.colliders.push_back(parseMovingCollider(collider));
    JsonReader gusts = scene.child("gusts");
    // Whole numbers, read exactly (a float would round seeds above 2^24).
    actors.gusts.count = uint32_t(gusts.integer("count", 0, 0, 100000));
    actors.gusts.seed = gusts.integer("seed", gustSeed, 0, UINT64_MAX);
    actors.gusts.height = gusts.numberF("height", actors.gusts.height, 0.0, 1000.0);
    gusts.finish();
    return actors;
}

} // namespace sward
