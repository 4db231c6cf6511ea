// Hashed value noise on a lattice in world metres (ground materials, the turf's wandering border): integer hashing
// (pcgHash of gpu_layout.h) and + - * only, so the colour and the truth pass, and every device, see the same values.
// Needs gpu_layout.h (frame.glsl) first.
#ifndef SWARD_HASH_NOISE_GLSL
#define SWARD_HASH_NOISE_GLSL

// The hash of lattice point c under `salt` (each layer of texture its own, so layers do not repeat each other).
float latticeHash(ivec2 c, uint salt) { return unitFromHash(pcgHash(uint(c.x) + pcgHash(uint(c.y) ^ salt))); }

// Value noise in [0, 1] on a lattice of `cell` metres with its gradient (per metre): x value, yz d/dx, d/dy. The
// corners are latticeHash's values, each row's hash of y taken once.
vec3 noiseWithGradient(vec2 xy, float cell, uint salt) {
    vec2 p = xy / cell, i = floor(p), f = p - i;
    ivec2 c = ivec2(i);
    uint y0 = pcgHash(uint(c.y) ^ salt), y1 = pcgHash(uint(c.y + 1) ^ salt);
    float n00 = unitFromHash(pcgHash(uint(c.x) + y0)), n10 = unitFromHash(pcgHash(uint(c.x + 1) + y0));
    float n01 = unitFromHash(pcgHash(uint(c.x) + y1)), n11 = unitFromHash(pcgHash(uint(c.x + 1) + y1));
    vec2 s = f * f * (3.0 - 2.0 * f), ds = 6.0 * f * (1.0 - f) / cell;
    float a = mix(n00, n10, s.x), b = mix(n01, n11, s.x);
    return vec3(mix(a, b, s.y), mix(n10 - n00, n11 - n01, s.y) * ds.x, (b - a) * ds.y);
}

float valueNoise(vec2 xy, float cell, uint salt) { return noiseWithGradient(xy, cell, salt).x; }

#endif
