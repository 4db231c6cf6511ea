// Scene actors that interact with the vegetation: wheeled vehicles driving along paths (one capsule collider
// per wheel, e.g. the four wheels of a skid-steer rover), free colliders moving along paths (mowers, rotor
// downwash, robots' feet) and drifting gusts. All poses are pure functions of simulation time.
#pragma once

#include "interaction/colliders.h"
#include "world/path.h"

#include <string>
#include <vector>

namespace sward {

class Ground;
class JsonReader;

struct VehicleParams {
    std::string name = "rover";
    PathParams path;              // the vehicle centre's path
    float wheelBase = 0.7f;       // metres between front and rear axles
    float trackWidth = 0.6f;      // metres between left and right wheel centres
    float wheelRadius = 0.15f;    // metres
    float wheelWidth = 0.12f;     // metres
    float weight = 2.0f;          // collider force: above a category's fell_force the wheels leave a track
    float sink = 0.02f;           // metres the wheels press into the sward below the terrain surface
    RutParams rut;                // the ruts the wheels leave in the ground (none by default)
};

struct MovingColliderParams {
    Collider collider;            // shape, size, kind, force, cut height; its position is the path's
    PathParams path;
};

struct GustParams {
    uint32_t count = 0;           // 0 = no gusts
    uint64_t seed = 1;
    float height = 0.3f;          // metres above the terrain's highest point: top of the gust centres' range
};

struct ActorParams {
    std::vector<VehicleParams> vehicles;
    std::vector<MovingColliderParams> colliders;
    GustParams gusts;
    bool empty() const { return vehicles.empty() && colliders.empty() && gusts.count == 0; }
};

// Wheel axle centre of wheel w (0 front-left, 1 front-right, 2 rear-left, 3 rear-right) and the heading.
struct WheelPose {
    glm::vec3 centre;
    glm::vec3 axle; // unit, pointing to the vehicle's left
};
std::vector<WheelPose> vehicleWheels(const VehicleParams& vehicle, const Ground& terrain, double time);
// The same wheels for the vehicle centre at `position` heading along the unit xy vector `heading` (a pose not
// given by a path, e.g. a vehicle driven from the keyboard in sward-view).
std::vector<WheelPose> vehicleWheelsAt(const VehicleParams& vehicle, const Ground& terrain, glm::dvec2 position,
                                       glm::dvec2 heading);
// One capsule collider per wheel (along the axle), ids 1000 * (index + 1) + w: what actorColliders uses.
std::vector<Collider> wheelColliders(const VehicleParams& vehicle, const std::vector<WheelPose>& wheels, uint32_t index);

// The free collider `index` of the scene (id 100000 + index) at simulation time `time`: what actorColliders uses.
Collider movingCollider(const MovingColliderParams& params, uint32_t index, const Ground& terrain, double time);

// Every collider of the scene's actors at simulation time `time` (tick = time / timeStep for gusts), with
// stable ids: vehicle v wheel w -> 1000 * (v + 1) + w, free collider i -> 100000 + i, gusts from 0x80000000.
std::vector<Collider> actorColliders(const ActorParams& actors, const Ground& terrain, double time, uint64_t tick,
                                     float timeStep);

// Reads the "vehicles", "colliders" and "gusts" keys (each optional) of the scene object `scene`; the gusts'
// seed defaults to `gustSeed` (the scene seed). Errors name the file and the JSON path ("vehicles[1].path").
ActorParams parseActors(JsonReader& scene, uint64_t gustSeed);

} // namespace sward
