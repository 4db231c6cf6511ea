#include "vegetation/records.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace sward {

namespace {

// Round half away from zero. Truncating a non-negative float is floor, and a cast compiles to one instruction
// where std::floor is a libm call on baseline x86-64; both are exact, so results are identical everywhere.
int32_t roundToInt(float v) {
    return v >= 0.0f ? int32_t(v + 0.5f) : -int32_t(-v + 0.5f);
}

uint32_t packSnorm16(float v) {
    return uint32_t(roundToInt(std::clamp(v, -1.0f, 1.0f) * 32767.0f)) & 0xffffu;
}
float unpackSnorm16(uint32_t bits) {
    return std::max(float(int16_t(uint16_t(bits))) / 32767.0f, -1.0f);
}
uint32_t packSnorm10(float v) {
    return uint32_t(roundToInt(std::clamp(v, -1.0f, 1.0f) * 511.0f)) & 0x3ffu;
}
float unpackSnorm10(uint32_t bits) {
    int32_t q = int32_t(bits & 0x3ffu);
    if (q >= 512) q -= 1024; // sign-extend 10 bits
    return std::max(float(q) / 511.0f, -1.0f);
}

} // namespace

uint32_t encodeOctahedral(glm::vec3 n) {
    float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    assert(l1 > 0.0f && std::isfinite(l1));
    glm::vec2 p = glm::vec2(n.x, n.y) / l1;
    if (n.z < 0.0f) {
        // Fold the lower hemisphere over the diagonals of the square.
        glm::vec2 folded(1.0f - std::abs(p.y), 1.0f - std::abs(p.x));
        p = glm::vec2(p.x >= 0.0f ? folded.x : -folded.x, p.y >= 0.0f ? folded.y : -folded.y);
    }
    return packSnorm16(p.x) | (packSnorm16(p.y) << 16);
}

glm::vec3 decodeOctahedral(uint32_t packed) {
    glm::vec2 f(unpackSnorm16(packed), unpackSnorm16(packed >> 16));
    glm::vec3 n(f.x, f.y, 1.0f - std::abs(f.x) - std::abs(f.y));
    float t = std::max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return n / std::sqrt(glm::dot(n, n));
}

gpu::PlantStatic encodePlantStatic(const PlantInstance& p) {
    assert(p.positionX < 65536 && p.positionY < 65536);
    assert(p.category < gpu::kMaxPlantCategories && p.variant < gpu::kMaxPlantVariants);
    assert(p.orientation < 256 && p.random < 256 && p.size < 256);
    return gpu::PlantStatic{
        .position = p.positionX | (p.positionY << 16),
        .height = std::bit_cast<uint32_t>(p.height),
        .up = encodeOctahedral(p.up),
        .attributes = p.category | (p.variant << 2) | (p.orientation << 8) | (p.random << 16) | (p.size << 24),
    };
}

PlantInstance decodePlantStatic(const gpu::PlantStatic& r) {
    return PlantInstance{
        .positionX = r.position & 0xffffu,
        .positionY = r.position >> 16,
        .height = std::bit_cast<float>(r.height),
        .up = decodeOctahedral(r.up),
        .category = r.attributes & 3u,
        .variant = (r.attributes >> 2) & 63u,
        .orientation = (r.attributes >> 8) & 255u,
        .random = (r.attributes >> 16) & 255u,
        .size = r.attributes >> 24,
    };
}

glm::vec2 decodePlanarPosition(uint32_t positionX, uint32_t positionY, glm::vec2 fieldOrigin, float positionStep) {
    // float(q) * step is exact (16-bit q times a step with few mantissa bits), so the only rounding is the add,
    // which the GPU performs identically.
    return fieldOrigin + glm::vec2(float(positionX), float(positionY)) * positionStep;
}

glm::vec3 decodePlantPosition(const gpu::PlantStatic& r, glm::vec2 fieldOrigin, float positionStep) {
    glm::vec2 xy = decodePlanarPosition(r.position & 0xffffu, r.position >> 16, fieldOrigin, positionStep);
    return glm::vec3(xy, std::bit_cast<float>(r.height));
}

float orientationRadians(uint32_t orientation) {
    return float(orientation) * (6.28318530718f / 256.0f);
}

gpu::PlantDynamic encodePlantDynamic(const PlantMotion& m) {
    uint32_t cut = uint32_t(roundToInt(std::clamp(m.cutFraction, 0.0f, 1.0f) * 255.0f));
    uint32_t velocity = packSnorm10(m.bendVelocity.x / gpu::kMaxBendVelocity) |
                        (packSnorm10(m.bendVelocity.y / gpu::kMaxBendVelocity) << 10);
    assert(m.state < 16);
    return gpu::PlantDynamic{
        .bend = packSnorm16(m.bend.x) | (packSnorm16(m.bend.y) << 16),
        .state = velocity | (m.state << 20) | (cut << 24),
    };
}

PlantMotion decodePlantDynamic(const gpu::PlantDynamic& r) {
    return PlantMotion{
        .bend = {unpackSnorm16(r.bend), unpackSnorm16(r.bend >> 16)},
        .bendVelocity = glm::vec2(unpackSnorm10(r.state), unpackSnorm10(r.state >> 10)) * gpu::kMaxBendVelocity,
        .state = (r.state >> 20) & 15u,
        .cutFraction = float(r.state >> 24) / 255.0f,
    };
}

} // namespace sward
