#include "vegetation/records.h"

#include "common/snorm.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace sward {

uint32_t encodeOctahedral(glm::vec3 n) {
    float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    assert(l1 > 0.0f && std::isfinite(l1));
    glm::vec2 p = glm::vec2(n.x, n.y) / l1;
    if (n.z < 0.0f) {
        // Fold the lower hemisphere over the diagonals of the square.
        glm::vec2 folded(1.0f - std::abs(p.y), 1.0f - std::abs(p.x));
        p = glm::vec2(p.x >= 0.0f ? folded.x : -folded.x, p.y >= 0.0f ? folded.y : -folded.y);
    }
    return packSnorm2x16(p.x, p.y);
}

glm::vec3 decodeOctahedral(uint32_t packed) {
    glm::vec2 f(unpackSnorm(packed, 16, SnormDivide::Exact), unpackSnorm(packed >> 16, 16, SnormDivide::Exact));
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
    uint32_t cut = uint32_t(roundHalfAway(std::clamp(m.cutFraction, 0.0f, 1.0f) * 255.0f));
    uint32_t velocity = packSnorm(m.bendVelocity.x / gpu::kMaxBendVelocity, 10) |
                        (packSnorm(m.bendVelocity.y / gpu::kMaxBendVelocity, 10) << 10);
    assert(m.state < 16);
    return gpu::PlantDynamic{
        .bend = packSnorm2x16(m.bend.x, m.bend.y),
        .state = velocity | (m.state << 20) | (cut << 24),
    };
}

PlantMotion decodePlantDynamic(const gpu::PlantDynamic& r) {
    return PlantMotion{
        .bend = {unpackSnorm(r.bend, 16, SnormDivide::Exact), unpackSnorm(r.bend >> 16, 16, SnormDivide::Exact)},
        .bendVelocity = glm::vec2(unpackSnorm(r.state, 10, SnormDivide::Exact),
                                  unpackSnorm(r.state >> 10, 10, SnormDivide::Exact)) *
                        gpu::kMaxBendVelocity,
        .state = (r.state >> 20) & 15u,
        .cutFraction = float(r.state >> 24) / 255.0f,
    };
}

} // namespace sward
