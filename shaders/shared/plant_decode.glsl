// Decoding of the compact plant records in plant_layout.h. Include plant_layout.h first.
// Mirrors vegetation/records.cpp bit for bit: the CPU tests decode with the C++ twin of every function here.
#ifndef SWARD_PLANT_DECODE_GLSL
#define SWARD_PLANT_DECODE_GLSL

// World position of a plant's base. field.originStep comes from the plant's PlantField.
vec3 plantPosition(PlantStatic p, vec4 fieldOriginStep) {
    vec2 q = vec2(float(p.position & 0xffffu), float(p.position >> 16));
    return vec3(fieldOriginStep.xy + q * fieldOriginStep.z, uintBitsToFloat(p.height));
}

// Octahedral decode (Cigolle et al. 2014): the square [-1,1]^2 folds onto the unit sphere.
vec3 octahedralDecode(uint packedUv) {
    vec2 f = unpackSnorm2x16(packedUv);
    vec3 n = vec3(f, 1.0 - abs(f.x) - abs(f.y));
    float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}

vec3 plantUp(PlantStatic p) { return octahedralDecode(p.up); }
uint plantCategory(PlantStatic p) { return bitfieldExtract(p.attributes, 0, 2); }
uint plantVariant(PlantStatic p) { return bitfieldExtract(p.attributes, 2, 6); }
// Rotation about the up vector in radians, [0, 2pi).
float plantOrientation(PlantStatic p) { return float(bitfieldExtract(p.attributes, 8, 8)) * (6.28318530718 / 256.0); }
// Per-plant random value in [0, 1].
float plantRandom(PlantStatic p) { return float(bitfieldExtract(p.attributes, 16, 8)) * (1.0 / 255.0); }
// Multiplier of the category's base height.
float plantSizeScale(PlantStatic p) { return float(bitfieldExtract(p.attributes, 24, 8)) / kPlantSizeDivisor; }

// Horizontal tip offset in plant heights.
vec2 plantBend(PlantDynamic d) { return unpackSnorm2x16(d.bend); }
// Bend velocity in plant heights per second.
vec2 plantBendVelocity(PlantDynamic d) {
    ivec2 q = ivec2(bitfieldExtract(int(d.state), 0, 10), bitfieldExtract(int(d.state), 10, 10)); // sign-extends
    return max(vec2(q) / 511.0, vec2(-1.0)) * kMaxBendVelocity;
}
uint plantState(PlantDynamic d) { return bitfieldExtract(d.state, 20, 4); }
// Remaining height fraction after cutting; 1 when uncut.
float plantCutFraction(PlantDynamic d) { return float(bitfieldExtract(d.state, 24, 8)) * (1.0 / 255.0); }

// Snorm quantisation that rounds half away from zero, identically to vegetation/records.cpp (the GLSL
// packSnorm* built-ins leave the rounding of halves to the implementation).
uint packSnormBits(float v, float scale, uint bits) {
    precise float x = clamp(v, -1.0, 1.0) * scale;
    int q = x >= 0.0 ? int(x + 0.5) : -int(-x + 0.5);
    return uint(q) & ((1u << bits) - 1u);
}

PlantDynamic packPlantDynamic(vec2 bend, vec2 bendVelocity, uint state, uint cutByte) {
    PlantDynamic d;
    d.bend = packSnormBits(bend.x, 32767.0, 16u) | (packSnormBits(bend.y, 32767.0, 16u) << 16);
    precise vec2 v = bendVelocity / kMaxBendVelocity;
    uint velocity = packSnormBits(v.x, 511.0, 10u) | (packSnormBits(v.y, 511.0, 10u) << 10);
    d.state = velocity | (state << 20) | (cutByte << 24);
    return d;
}

#endif
