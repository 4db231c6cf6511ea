// The keys that describe a collider's shape ("shape", "kind", "radius", "force", "length", "half_extents",
// "cut_height", and its ruts; docs/scene-format.md), shared by the scene's moving colliders (scene/vehicles.h) and the colliders a
// program places at each tick (the Python module's set_colliders).
#pragma once

#include "interaction/colliders.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

class JsonReader;

// The ruts a push collider leaves ("rut_depth", "tread_pitch", "tread_depth"; all 0 by default: none). Errors name
// the key: a rut on a collider that is not a push, a tread deeper than the rut, a tread without a pitch.
RutParams parseRut(JsonReader& r, ColliderKind kind);

// A collider of the shape `r` describes, centred at the origin (a capsule along x, a box axis-aligned), id 0.
// Reads the shape keys only; the caller finishes `r`.
Collider parseColliderShape(JsonReader& r);

// Ids of placed colliders: kPlacedColliderBase + index, apart from every id of sceneColliders (scene/vehicles.h,
// scene/objects.h) and below the gusts' 0x80000000.
inline constexpr uint32_t kPlacedColliderBase = 0x40000000u;
inline constexpr size_t kMaxPlacedColliders = 10000;

// A JSON array of colliders, each the shape keys plus "centre": [x, y, z] (world metres, required); ids
// kPlacedColliderBase + index. Errors name `source` and the element: "colliders: '[1].radius' must be ...".
std::vector<Collider> parsePlacedColliders(const nlohmann::json& colliders, const std::string& source);

} // namespace sward
