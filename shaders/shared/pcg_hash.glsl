// Integer hashing for shading decisions that must be the same on every device (no sin, no float noise).
#ifndef SWARD_PCG_HASH_GLSL
#define SWARD_PCG_HASH_GLSL

// PCG's output permutation (Jarzynski and Olano, "Hash Functions for GPU Rendering", 2020).
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A hash's top 24 bits as a number in [0, 1).
float unitFromHash(uint h) { return float(h >> 8) * (1.0 / 16777216.0); }

#endif
