#include "interaction/colliders.h"

#include "common/hash.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sward {

namespace {

[[maybe_unused]] bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 closestOnSegment(glm::vec3 a, glm::vec3 b, glm::vec3 p) {
    glm::vec3 ab = b - a;
    float len2 = glm::dot(ab, ab);
    if (len2 <= 0.0f) return a; // degenerate capsule: a sphere
    float t = std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f);
    return a + ab * t;
}

} // namespace

Collider makeSphere(uint32_t id, glm::vec3 centre, float radius, float force, ColliderKind kind) {
    assert(finite(centre) && radius > 0.0f && force >= 0.0f);
    return Collider{.id = id,
                    .shape = ColliderShape::Sphere,
                    .kind = kind,
                    .centre = centre,
                    .end = centre,
                    .radius = radius,
                    .force = force};
}

Collider makeCapsule(uint32_t id, glm::vec3 a, glm::vec3 b, float radius, float force, ColliderKind kind) {
    assert(finite(a) && finite(b) && radius > 0.0f && force >= 0.0f);
    return Collider{.id = id,
                    .shape = ColliderShape::Capsule,
                    .kind = kind,
                    .centre = a,
                    .end = b,
                    .radius = radius,
                    .force = force};
}

Collider makeBox(uint32_t id, glm::vec3 centre, glm::vec3 halfExtents, const glm::mat3& rotation, float force,
                 ColliderKind kind) {
    assert(finite(centre) && halfExtents.x > 0.0f && halfExtents.y > 0.0f && halfExtents.z > 0.0f && force >= 0.0f);
    return Collider{.id = id,
                    .shape = ColliderShape::Box,
                    .kind = kind,
                    .centre = centre,
                    .end = centre,
                    .radius = 0.0f,
                    .halfExtents = halfExtents,
                    .rotation = rotation,
                    .force = force};
}

Collider makeMower(Collider hull, float cutHeight) {
    assert(std::isfinite(cutHeight) && cutHeight >= 0.0f);
    hull.kind = ColliderKind::Mower;
    hull.cutHeight = cutHeight;
    return hull;
}

Collider makeDownwash(uint32_t id, glm::vec3 rotor, float radius, float reach, float force) {
    assert(reach > 0.0f);
    return makeCapsule(id, rotor, rotor - glm::vec3(0.0f, 0.0f, reach), radius, force, ColliderKind::Downwash);
}

std::vector<Collider> makeGusts(uint64_t seed, uint32_t count, const Aabb& area, uint64_t tick, float timeStep,
                                uint32_t firstId) {
    assert(area.min.x < area.max.x && area.min.y < area.max.y && area.min.z <= area.max.z && timeStep > 0.0f);
    constexpr uint64_t kGustDomain = 0x6775737473ull; // "gusts": keeps these hashes apart from placement's
    const glm::vec2 lo(area.min), extent = glm::vec2(area.max) - lo;
    // Time in seconds as a double, so positions do not lose precision after hours of ticks.
    const double seconds = double(tick) * double(timeStep);
    std::vector<Collider> gusts;
    gusts.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        HashStream s{hashKey({kGustDomain, seed, i})};
        float radius = 1.0f + 3.0f * s.nextFloat();
        float force = 0.15f + 0.35f * s.nextFloat();
        glm::vec2 start = lo + extent * glm::vec2(s.nextFloat(), s.nextFloat());
        float z = area.min.z + (area.max.z - area.min.z) * s.nextFloat();
        // A direction from a hashed square point, normalised with sqrt only (no libm trigonometry).
        glm::vec2 dir(2.0f * s.nextFloat() - 1.0f, 2.0f * s.nextFloat() - 1.0f);
        float len2 = glm::dot(dir, dir);
        dir = len2 > 1e-6f ? dir / std::sqrt(len2) : glm::vec2(1.0f, 0.0f);
        float speed = 1.0f + 3.0f * s.nextFloat();
        glm::dvec2 travelled = glm::dvec2(start - lo) + glm::dvec2(dir) * double(speed) * seconds;
        // Wrap into the area so the gusts keep drifting over it forever.
        glm::dvec2 e(extent);
        glm::dvec2 wrapped = travelled - glm::floor(travelled / e) * e;
        glm::vec3 centre(lo + glm::vec2(wrapped), z);
        gusts.push_back(makeSphere(firstId + i, centre, radius, force, ColliderKind::Gust));
    }
    return gusts;
}

float signedDistance(const Collider& c, glm::vec3 p) {
    switch (c.shape) {
    case ColliderShape::Sphere:
        return glm::length(p - c.centre) - c.radius;
    case ColliderShape::Capsule:
        return glm::length(p - closestOnSegment(c.centre, c.end, p)) - c.radius;
    case ColliderShape::Box: {
        glm::vec3 q = glm::abs(glm::transpose(c.rotation) * (p - c.centre)) - c.halfExtents;
        float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
        float inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
        return outside + inside;
    }
    }
    return 0.0f;
}

glm::vec3 axisPoint(const Collider& c, glm::vec3 p) {
    switch (c.shape) {
    case ColliderShape::Sphere:
        return c.centre;
    case ColliderShape::Capsule:
        return closestOnSegment(c.centre, c.end, p);
    case ColliderShape::Box: {
        glm::vec3 core = c.halfExtents - std::min(c.halfExtents.x, std::min(c.halfExtents.y, c.halfExtents.z));
        glm::vec3 local = glm::clamp(glm::transpose(c.rotation) * (p - c.centre), -core, core);
        return c.centre + c.rotation * local;
    }
    }
    return c.centre;
}

Aabb worldBounds(const Collider& c) {
    switch (c.shape) {
    case ColliderShape::Sphere:
        return {c.centre - c.radius, c.centre + c.radius};
    case ColliderShape::Capsule:
        return {glm::min(c.centre, c.end) - c.radius, glm::max(c.centre, c.end) + c.radius};
    case ColliderShape::Box: {
        // Half extent of the rotated box along each world axis: sum of |axis component| * half extent.
        glm::mat3 a(glm::abs(c.rotation[0]), glm::abs(c.rotation[1]), glm::abs(c.rotation[2]));
        glm::vec3 e = a * c.halfExtents;
        return {c.centre - e, c.centre + e};
    }
    }
    return {c.centre, c.centre};
}

} // namespace sward
