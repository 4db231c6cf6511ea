#include "interaction/recovery.h"

#include "common/snorm.h"

#include <algorithm>

namespace sward {

namespace {

// Bit-for-bit twin of shaders/shared/recovery.glsl. Only + - * and comparisons (correctly rounded on every
// Vulkan device; division and sqrt are not), no contraction (-ffp-contract=off here, `precise` there), and
// snorm rounding half away from zero; snorms decode by multiplying with the reciprocal for the same reason.
struct Motion {
    float bx, by, vx, vy;
    uint32_t state, cut;
};

float unpack16(uint32_t bits) {
    return unpackSnorm(bits, 16, SnormDivide::ByReciprocal);
}
float unpack10(uint32_t bits) {
    return unpackSnorm(bits, 10, SnormDivide::ByReciprocal);
}

Motion decode(const gpu::PlantDynamic& r) {
    return {unpack16(r.bend), unpack16(r.bend >> 16), unpack10(r.state) * gpu::kMaxBendVelocity,
            unpack10(r.state >> 10) * gpu::kMaxBendVelocity, (r.state >> 20) & 15u, r.state >> 24};
}

gpu::PlantDynamic encode(const Motion& m) {
    const float toUnit = 1.0f / gpu::kMaxBendVelocity; // 0.25: exact
    return {packSnorm2x16(m.bx, m.by),
            packSnorm(m.vx * toUnit, 10) | (packSnorm(m.vy * toUnit, 10) << 10) | (m.state << 20) | (m.cut << 24)};
}

} // namespace

gpu::PlantDynamic applyContact(gpu::PlantDynamic record, const gpu::PlantContact& contact, const RecoveryParams&) {
    Motion m = decode(record);
    if (m.state == gpu::kPlantStateFelled) return record; // stays down for good
    uint32_t kind = contact.flags & 15u;
    float px = unpack16(contact.push), py = unpack16(contact.push >> 16);
    if (kind == gpu::kContactFell) {
        // The collision pass sends the final flattened tip offset (direction * fellBend).
        m.bx = px;
        m.by = py;
        m.vx = m.vy = 0.0f;
        m.state = gpu::kPlantStateFelled;
        return encode(m);
    }
    if (kind == gpu::kContactCut) {
        m.cut = std::min(m.cut, (contact.flags >> 8) & 255u);
        m.state = gpu::kPlantStateCut;
    } else if (m.state != gpu::kPlantStateCut) {
        m.state = gpu::kPlantStateRecovering;
    }
    // The collider holds the tip where it pushes it: the larger of the current bend and the push wins.
    if (px * px + py * py >= m.bx * m.bx + m.by * m.by) {
        m.bx = px;
        m.by = py;
    }
    m.vx = m.vy = 0.0f;
    return encode(m);
}

gpu::PlantDynamic recoverStep(gpu::PlantDynamic record, const RecoveryParams& p) {
    Motion m = decode(record);
    if (m.state == gpu::kPlantStateFelled || m.state == gpu::kPlantStateRest) return record;
    if (m.bx == 0.0f && m.by == 0.0f && m.vx == 0.0f && m.vy == 0.0f) return record; // resting cut plant
    // Semi-implicit Euler of a damped spring: v += (-k b - c v) dt; b += v dt.
    float ax = -p.stiffness * m.bx - p.damping * m.vx;
    float ay = -p.stiffness * m.by - p.damping * m.vy;
    m.vx = m.vx + ax * p.timeStep;
    m.vy = m.vy + ay * p.timeStep;
    m.bx = m.bx + m.vx * p.timeStep;
    m.by = m.by + m.vy * p.timeStep;
    float rest2 = p.restBend * p.restBend;
    if (m.bx * m.bx + m.by * m.by < rest2 && m.vx * m.vx + m.vy * m.vy < rest2) {
        m.bx = m.by = m.vx = m.vy = 0.0f;
        if (m.state == gpu::kPlantStateRecovering) m.state = gpu::kPlantStateRest;
    }
    return encode(m);
}

bool plantSettled(const gpu::PlantDynamic& record) {
    uint32_t state = (record.state >> 20) & 15u;
    if (state == gpu::kPlantStateFelled) return true;
    return record.bend == 0u && (record.state & 0xfffffu) == 0u;
}

} // namespace sward
