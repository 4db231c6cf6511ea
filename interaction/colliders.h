// Colliders: the simplified hulls that push, fell and cut plants (paper 3.3, issue 6).
//
// A collider is a sphere, a capsule (segment + radius) or an oriented box, attached to a scene object (e.g. one per
// wheel) or free, with a kind that decides how it acts on the plants it penetrates:
//   Push      solid bodies (wheels, feet, robot hulls): bend plants away from the hull's axis; a force above the
//             plant category's fell threshold flattens them for good (tracks);
//   Gust      a local breeze: a drifting sphere that only bends (makeGusts);
//   Downwash  the air column below a hovering rotor: a vertical capsule that bends plants radially outward, weaker
//             towards its rim and its lower end (makeDownwash);
//   Mower     cuts the plants it touches to cutHeight above their base, and bends them.
// Everything here is a pure function of its arguments: no clocks, no std:: random (gusts hash with sward::hashKey).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sward {

enum class ColliderShape : uint32_t { Sphere, Capsule, Box };
enum class ColliderKind : uint32_t { Push, Gust, Downwash, Mower };

// Axis-aligned box; min <= max on every axis.
struct Aabb {
    glm::vec3 min{0.0f}, max{0.0f};
    bool overlaps(const Aabb& o) const {
        return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y && min.z <= o.max.z &&
               o.min.z <= max.z;
    }
};

// Ruts a collider presses into the ground it rolls or slides over (interaction/ground_tracks.h); depth 0: none.
// With a tread, the rut's floor rises by treadDepth between lugs: a groove every treadPitch metres along the
// direction the collider moves, half a pitch wide.
struct RutParams {
    float depth = 0.0f;      // metres below the ground where the hull rests on it
    float treadPitch = 0.0f; // metres between lugs; 0: a smooth rut
    float treadDepth = 0.0f; // metres, at most depth
};

struct Collider {
    uint32_t id = 0; // stable identity: several colliders on one plant combine in id order
    ColliderShape shape = ColliderShape::Sphere;
    ColliderKind kind = ColliderKind::Push;
    glm::vec3 centre{0.0f};      // sphere and box centre; capsule segment start
    glm::vec3 end{0.0f};         // capsule segment end
    float radius = 0.5f;         // sphere and capsule, metres
    glm::vec3 halfExtents{0.5f}; // box, metres along its own axes
    glm::mat3 rotation{1.0f};    // box: columns are its axes in world space (orthonormal)
    float force = 0.5f;          // dimensionless push strength; also the weight compared with fell thresholds
    float cutHeight = 0.0f;      // mower: metres above the plant base
    RutParams rut;               // push colliders only: the ruts it leaves in the ground
};

// Factories; each requires finite arguments, radius / half extents > 0 and force >= 0 (asserted).
Collider makeSphere(uint32_t id, glm::vec3 centre, float radius, float force, ColliderKind kind = ColliderKind::Push);
Collider makeCapsule(uint32_t id, glm::vec3 a, glm::vec3 b, float radius, float force,
                     ColliderKind kind = ColliderKind::Push);
// rotation: orthonormal columns (the box's axes in world space).
Collider makeBox(uint32_t id, glm::vec3 centre, glm::vec3 halfExtents, const glm::mat3& rotation, float force,
                 ColliderKind kind = ColliderKind::Push);
// A mower blade: the hull turned into a Mower cutting at cutHeight (>= 0) metres above each plant's base.
Collider makeMower(Collider hull, float cutHeight);
// Downwash of a rotor at `rotor`: a vertical capsule of `radius` reaching `reach` metres down (reach > 0).
Collider makeDownwash(uint32_t id, glm::vec3 rotor, float radius, float reach, float force);

// Deterministic local breezes: `count` Gust spheres (ids firstId, firstId + 1, ...) with hashed radius (1..4 m),
// force (0.15..0.5), start position and drift velocity (1..4 m/s); their xy drifts with tick * timeStep and wraps
// around area's xy, their centre height is hashed in area's z range. A pure function of its arguments.
std::vector<Collider> makeGusts(uint64_t seed, uint32_t count, const Aabb& area, uint64_t tick,
                                float timeStep = 1.0f / 30.0f, uint32_t firstId = 0x80000000u);

// Signed distance from p to the hull's surface, metres: negative inside (exact for all three shapes).
float signedDistance(const Collider& c, glm::vec3 p);
// The point of the hull's core nearest to p, from which plants are pushed away: the sphere centre, the nearest
// point of the capsule segment, or for a box the nearest point of the box shrunk by its smallest half extent (the
// centre of a cube, the mid-line of an elongated box) so each plant is pushed out through the nearest side.
glm::vec3 axisPoint(const Collider& c, glm::vec3 p);
// World-space bounds enclosing the whole hull.
Aabb worldBounds(const Collider& c);

} // namespace sward
