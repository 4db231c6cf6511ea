// Encoding and decoding of the compact plant records declared in shaders/shared/plant_layout.h.
//
// The C++ twin of shaders/shared/plant_decode.glsl: the tests decode records with these functions, so a
// change of the bit layout must be made in both files. Encoding uses only + - * / floor and sqrt, so records
// are bitwise identical on every x86-64 machine.
#pragma once

#include "shared/plant_layout.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace sward {

// Everything a PlantStatic record stores, in natural units.
struct PlantInstance {
    uint32_t positionX = 0, positionY = 0; // quantised steps from the field's min corner, 0..65535
    float height = 0.0f;                   // world z of the base, metres
    glm::vec3 up{0.0f, 0.0f, 1.0f};        // unit vector
    uint32_t category = 0;                 // atlas row, < kMaxPlantCategories
    uint32_t variant = 0;                  // atlas column, < kMaxPlantVariants
    uint32_t orientation = 0;              // angle in 1/256 turns, 0..255
    uint32_t random = 0;                   // 0..255
    uint32_t size = 128;                   // height scale in 1/128, 1..255
};

// Interaction state in natural units.
struct PlantMotion {
    glm::vec2 bend{0.0f};         // horizontal tip offset in plant heights, each component in [-1, 1]
    glm::vec2 bendVelocity{0.0f}; // plant heights per second, each component in [-kMaxBendVelocity, +]
    uint32_t state = gpu::kPlantStateRest;
    float cutFraction = 1.0f; // remaining height fraction, 1 = uncut
};

// Octahedral encoding of a unit vector into 2 x snorm16. Requires a finite, non-zero vector.
uint32_t encodeOctahedral(glm::vec3 unit);
// Inverse of encodeOctahedral: a unit vector.
glm::vec3 decodeOctahedral(uint32_t packed);

// Packs a plant. Requires every field within its documented range (asserted).
gpu::PlantStatic encodePlantStatic(const PlantInstance& plant);
// Unpacks a plant record (up is decoded, so it differs from the encoded vector by the quantisation error).
PlantInstance decodePlantStatic(const gpu::PlantStatic& record);

// World position of a plant's base, computed exactly like plantPosition() in plant_decode.glsl.
glm::vec3 decodePlantPosition(const gpu::PlantStatic& record, glm::vec2 fieldOrigin, float positionStep);
// The xy part alone, used while generating so that the height is taken at the decoded position.
glm::vec2 decodePlanarPosition(uint32_t positionX, uint32_t positionY, glm::vec2 fieldOrigin, float positionStep);

// Orientation about up in radians, [0, 2pi).
float orientationRadians(uint32_t orientation);

// Packs interaction state (values are clamped to the representable range).
gpu::PlantDynamic encodePlantDynamic(const PlantMotion& motion);
PlantMotion decodePlantDynamic(const gpu::PlantDynamic& record);
// The state of a plant nobody has touched yet: upright, at rest, uncut.
inline gpu::PlantDynamic restingPlantDynamic() {
    return encodePlantDynamic(PlantMotion{});
}

} // namespace sward
