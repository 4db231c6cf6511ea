// Plant interaction dynamics per fixed tick, the GPU twin of vegetation/recovery.cpp (bit for bit): only
// + - * and comparisons, all `precise` (no FMA contraction), snorm rounding half away from zero.
#ifndef SWARD_RECOVERY_GLSL
#define SWARD_RECOVERY_GLSL

struct Motion {
    float bx, by, vx, vy;
    uint state, cut;
};

const float kInv32767 = 1.0 / 32767.0;
const float kInv511 = 1.0 / 511.0;

int roundHalfAway(float x) { return x >= 0.0 ? int(x + 0.5) : -int(-x + 0.5); }
uint packSnorm(float v, float scale, uint bits) {
    precise float x = clamp(v, -1.0, 1.0) * scale;
    return uint(roundHalfAway(x)) & ((1u << bits) - 1u);
}
float unpackS16(uint bits) { return max(float(bitfieldExtract(int(bits), 0, 16)) * kInv32767, -1.0); }
float unpackS10(uint bits) { return max(float(bitfieldExtract(int(bits), 0, 10)) * kInv511, -1.0); }

Motion decodeMotion(PlantDynamic r) {
    precise float vx = unpackS10(r.state) * kMaxBendVelocity;
    precise float vy = unpackS10(r.state >> 10) * kMaxBendVelocity;
    return Motion(unpackS16(r.bend), unpackS16(r.bend >> 16), vx, vy, bitfieldExtract(r.state, 20, 4), r.state >> 24);
}

PlantDynamic encodeMotion(Motion m) {
    const float toUnit = 1.0 / kMaxBendVelocity;
    precise float ux = m.vx * toUnit, uy = m.vy * toUnit;
    PlantDynamic r;
    r.bend = packSnorm(m.bx, 32767.0, 16u) | (packSnorm(m.by, 32767.0, 16u) << 16);
    r.state = packSnorm(ux, 511.0, 10u) | (packSnorm(uy, 511.0, 10u) << 10) | (m.state << 20) | (m.cut << 24);
    return r;
}

PlantDynamic applyContact(PlantDynamic record, PlantContact contact) {
    Motion m = decodeMotion(record);
    if (m.state == kPlantStateFelled) return record; // stays down for good
    uint kind = contact.flags & 15u;
    float px = unpackS16(contact.push), py = unpackS16(contact.push >> 16);
    if (kind == kContactFell) { // the collision pass sends the final flattened tip offset
        m.bx = px;
        m.by = py;
        m.vx = 0.0;
        m.vy = 0.0;
        m.state = kPlantStateFelled;
        return encodeMotion(m);
    }
    if (kind == kContactCut) {
        m.cut = min(m.cut, (contact.flags >> 8) & 255u);
        m.state = kPlantStateCut;
    } else if (m.state != kPlantStateCut) {
        m.state = kPlantStateRecovering;
    }
    precise float push2 = px * px + py * py;
    precise float bend2 = m.bx * m.bx + m.by * m.by;
    if (push2 >= bend2) {
        m.bx = px;
        m.by = py;
    }
    m.vx = 0.0;
    m.vy = 0.0;
    return encodeMotion(m);
}

PlantDynamic recoverStep(PlantDynamic record, RecoveryConstants p) {
    Motion m = decodeMotion(record);
    if (m.state == kPlantStateFelled || m.state == kPlantStateRest) return record;
    if (m.bx == 0.0 && m.by == 0.0 && m.vx == 0.0 && m.vy == 0.0) return record; // resting cut plant
    float dt = p.spring.x, k = p.spring.y, c = p.spring.z, rest = p.spring.w;
    precise float ax = -k * m.bx - c * m.vx;
    precise float ay = -k * m.by - c * m.vy;
    precise float vx = m.vx + ax * dt;
    precise float vy = m.vy + ay * dt;
    precise float bx = m.bx + vx * dt;
    precise float by = m.by + vy * dt;
    precise float bend2 = bx * bx + by * by;
    precise float speed2 = vx * vx + vy * vy;
    precise float rest2 = rest * rest;
    m.bx = bx;
    m.by = by;
    m.vx = vx;
    m.vy = vy;
    if (bend2 < rest2 && speed2 < rest2) {
        m.bx = 0.0;
        m.by = 0.0;
        m.vx = 0.0;
        m.vy = 0.0;
        if (m.state == kPlantStateRecovering) m.state = kPlantStateRest;
    }
    return encodeMotion(m);
}

#endif
