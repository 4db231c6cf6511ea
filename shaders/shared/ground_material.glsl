// Ground materials (issue 46): what bare ground and the ground under the plants look like, as albedo plus a bump
// slope for the lighting, in world metres so the texture stays on the ground as the camera moves. Everything is
// value noise from integer hashing (no sin, no texture), the same on every device.
//
// Each octave is filtered by the pixel's footprint on the ground: it fades to its mean (0.5) where the footprint
// reaches half its cell, so the far ground neither aliases nor flickers; octaves below the footprint are not
// computed at all, which is also what keeps a far pixel cheap. The texture changes colour only: the drawn surface,
// its depth and its ground-truth normal stay the mesh's.
//
// Presets (gpu_layout.h kGroundMaterial*, scene key terrain.material): soil, dry_soil, mud, gravel, forest_floor.
// Albedos are linear, chosen for the saturation and value of photographed soils (dry loam, wet clay, road gravel,
// leaf litter) after the preview's tone curve. Needs frame.glsl first.
#ifndef SWARD_GROUND_MATERIAL_GLSL
#define SWARD_GROUND_MATERIAL_GLSL

#include "shared/hash_noise.glsl"

struct GroundMaterial {
    vec3 albedo;    // mean linear albedo
    vec3 patchTint; // albedo of the field-scale patches (wetter / drier / organic) the base blends with
    vec3 speck;     // albedo of the small things lying on it: pebbles, dead leaves, straw
    float relief;   // bump slope of the clods and grains (0: flat)
    float specks;   // share of the ground the specks cover at near range
    float speckSize;// metres
    float cracks;   // darkening along the cracks between clods (dry soil)
    float clodSize; // metres across a clod (0: none), each a dome of its own shade and tint
    float hueJitter;// per-clod / per-speck hue variation (0: none)
};

GroundMaterial groundMaterialPreset(uint preset) {
    if (preset == kGroundMaterialDrySoil) // cracked, pale, large clods
        return GroundMaterial(vec3(0.20, 0.175, 0.145), vec3(0.25, 0.22, 0.185), vec3(0.30, 0.29, 0.27), 0.45, 0.04,
                              0.012, 0.7, 0.25, 0.5);
    if (preset == kGroundMaterialMud) // dark, wet, smooth
        return GroundMaterial(vec3(0.072, 0.062, 0.052), vec3(0.05, 0.044, 0.038), vec3(0.11, 0.10, 0.09), 0.3, 0.02,
                              0.01, 0.0, 0.0, 0.4);
    if (preset == kGroundMaterialGravel) // stones over a grey-brown matrix
        return GroundMaterial(vec3(0.16, 0.152, 0.14), vec3(0.13, 0.122, 0.11), vec3(0.26, 0.255, 0.245), 0.4, 0.5,
                              0.014, 0.0, 0.0, 1.0);
    if (preset == kGroundMaterialForestFloor) // brown leaf litter over dark humus
        return GroundMaterial(vec3(0.080, 0.064, 0.048), vec3(0.06, 0.05, 0.04), vec3(0.19, 0.13, 0.07), 0.5, 0.55,
                              0.03, 0.0, 0.0, 1.0);
    // kGroundMaterialSoil: moist loam in clods, a few pebbles and bits of dead plant.
    return GroundMaterial(vec3(0.125, 0.110, 0.094), vec3(0.098, 0.085, 0.068), vec3(0.20, 0.19, 0.175), 0.28, 0.06,
                          0.008, 0.2, 0.16, 0.8);
}

// m + w * a, field by field.
void addGroundMaterial(inout GroundMaterial m, GroundMaterial a, float w) {
    m.albedo += w * a.albedo;
    m.patchTint += w * a.patchTint;
    m.speck += w * a.speck;
    m.relief += w * a.relief;
    m.specks += w * a.specks;
    m.speckSize += w * a.speckSize;
    m.cracks += w * a.cracks;
    m.clodSize += w * a.clodSize;
    m.hueJitter += w * a.hueJitter;
}

// The ground where the vegetation categories grow with `weights` (their grass-map values) on `terrain`'s ground:
// every parameter the weighted mean of the categories' presets (`presets`: 8 bits each, category 0 lowest) and the
// terrain's, which keeps the weight left, max(0, 1 - sum). Weights summing to more than 1 are scaled to 1.
GroundMaterial blendGroundMaterials(GroundMaterial terrain, uint presets, vec4 weights) {
    float sum = weights.x + weights.y + weights.z + weights.w;
    weights /= max(sum, 1.0);
    GroundMaterial m = GroundMaterial(vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    addGroundMaterial(m, terrain, max(0.0, 1.0 - sum));
    for (uint c = 0u; c < 4u; ++c)
        if (weights[c] > 0.0) addGroundMaterial(m, groundMaterialPreset((presets >> (8u * c)) & 0xffu), weights[c]);
    return m;
}

// How much of an octave of `cell` metres survives a pixel footprint of `footprint` metres: all of it up to a quarter
// cell, none from half a cell on (its mean is what the pixel would average to).
float octaveWeight(float cell, float footprint) { return clamp(2.0 - 4.0 * footprint / cell, 0.0, 1.0); }

// A pixel's footprint on the ground, metres: between the short and the long axis of its ellipse, so a grazing view
// keeps the texture across the line of sight (a little aliasing along it) instead of smearing it all.
float groundFootprint(vec3 world) {
    float a = length(dFdx(world.xy)), b = length(dFdy(world.xy));
    return max(min(a, b), 0.35 * max(a, b));
}

// Specks: at most one small thing per lattice cell (pebble, leaf, straw), at a hashed spot and size. Returns its
// coverage of the point in [0, 1] (soft-edged over the footprint) and, in yz, its dome's bump slope.
vec3 speckAt(vec2 xy, float size, float share, float footprint, uint salt) {
    float cell = 2.5 * size;
    vec2 p = xy / cell;
    ivec2 c = ivec2(floor(p));
    if (latticeHash(c, salt) >= share * 4.4) return vec3(0.0); // a cell is 4.4x a mean speck's area
    vec2 centre = (vec2(c) + 0.2 + 0.6 * vec2(latticeHash(c, salt + 1u), latticeHash(c, salt + 2u))) * cell;
    float radius = size * (0.35 + 0.65 * latticeHash(c, salt + 3u));
    vec2 d = xy - centre;
    float r = length(d), edge = max(footprint, 0.15 * radius);
    float cover = clamp((radius - r) / edge + 0.5, 0.0, 1.0);
    return vec3(cover, cover * -d / max(radius, 1e-4));
}

// Clods: a jittered lattice of `size` metres, each point of the ground belonging to its nearest centre (Worley's
// cellular texture). x: the clod's dome height in [0, 1], y: the gap to the next clod's border (metres; small in the
// cracks), z: the clod's own hash; w unused. `toCentre` the offset from the centre, for the dome's slope.
vec4 clodAt(vec2 xy, float size, uint salt, out vec2 toCentre) {
    vec2 p = xy / size;
    ivec2 c = ivec2(floor(p));
    float f1 = 1e9, f2 = 1e9;
    ivec2 nearest = c;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = c + ivec2(i, j);
            // One hash per cell: its low and high halves place the centre (the cell's cost on a CPU driver).
            uint h = pcgHash(uint(q.x) + pcgHash(uint(q.y) ^ salt));
            vec2 centre = vec2(q) + 0.15 + (0.7 / 65536.0) * vec2(float(h & 0xffffu), float(h >> 16u));
            float d = dot(p - centre, p - centre);
            if (d < f1) {
                f2 = f1;
                f1 = d;
                nearest = q;
                toCentre = (p - centre) * size;
            } else if (d < f2) {
                f2 = d;
            }
        }
    float r1 = sqrt(f1), r2 = sqrt(f2);
    return vec4(clamp(1.0 - r1 * r1 * 1.6, 0.0, 1.0), (r2 - r1) * 0.5 * size, latticeHash(nearest, salt + 2u), 0.0);
}

struct GroundSample {
    vec3 albedo;
    vec2 slope; // bump: dh/dx, dh/dy of the texture's relief, to tilt the shading normal
};

// Bare ground of `m` at world point xy, seen with a pixel footprint of `footprint` metres.
GroundSample bareGround(GroundMaterial m, vec2 xy, float footprint) {
    // Field scale: wetter and drier patches of a few metres (value), organic-rich and sandy ones (hue).
    float patches = valueNoise(xy, 4.0, 11u) * 0.6 + valueNoise(xy, 1.3, 12u) * 0.4;
    vec2 hue = vec2(valueNoise(xy, 2.2, 13u), valueNoise(xy, 0.8, 14u)) - 0.5;
    vec3 albedo = mix(m.albedo, m.patchTint, smoothstep(0.3, 0.8, patches));
    albedo *= vec3(1.0 + 0.2 * hue.x, 1.0 + 0.1 * hue.y, 1.0 - 0.25 * hue.x); // redder / yellower / greyer-green
    // Clods and grains: octaves from 40 cm down to 3 mm, each relief about as steep as the next (fractal soil),
    // each also a little lighter on top (dry crust) and darker in its hollows.
    vec2 slope = vec2(0.0);
    float shade = 0.0;
    float cell = 0.4;
    for (uint k = 0u; k < 7u; ++k, cell *= 0.45) {
        float w = octaveWeight(cell, footprint);
        if (w <= 0.0) break;
        vec3 n = noiseWithGradient(xy, cell, 20u + k);
        slope += w * m.relief * cell * n.yz * 0.5;
        shade += w * (n.x - 0.5) * (k < 3u ? 0.35 : 0.5);
    }
    albedo *= 1.0 + shade;
    // Clods with cracks between them, each its own shade and tint, lit as low domes: large ones, and small ones
    // on them. The lattice is warped so that no two clods have the same shape, and clods gather in patches with
    // finer, smoother soil between (a field is not cobbled).
    float cloddy = 0.5 + 0.5 * smoothstep(0.25, 0.65, valueNoise(xy, 1.7, 37u));
    for (uint k = 0u; k < 2u; ++k) {
        float size = k == 0u ? m.clodSize : m.clodSize * 0.45;
        float wc = size > 0.0 ? octaveWeight(size * 0.75, footprint) * cloddy : 0.0;
        if (wc <= 0.0) break;
        vec2 warp = vec2(valueNoise(xy, size * 1.3, 32u + k), valueNoise(xy, size * 1.3, 34u + k)) - 0.5;
        vec2 toCentre;
        vec4 clod = clodAt(xy + size * 0.45 * warp, size, 30u + 4u * k, toCentre);
        float own = clod.z - 0.5, strength = k == 0u ? 1.0 : 0.9;
        albedo *= 1.0 + wc * strength * (0.32 * own + 0.1 * (clod.x - 0.5));
        albedo *= 1.0 + wc * strength * m.hueJitter * 0.35 * vec3(own, 0.1 * own, -own);
        // Cracks open only in patches (where the soil dried), not around every clod.
        float open = smoothstep(0.45, 0.75, valueNoise(xy, 0.6, 36u + k));
        float crack = open * (1.0 - smoothstep(0.0, max(0.06 * size, footprint), clod.y));
        albedo *= 1.0 - wc * m.cracks * crack * (k == 0u ? 1.0 : 0.5);
        // The dome flattens towards the clod's border, so neighbouring clods meet without a seam of light.
        float dome = smoothstep(0.0, 0.08 * size, clod.y);
        slope -= wc * strength * dome * (clod.x > 0.0 ? 0.45 : 0.15) * toCentre / size;
    }
    // Specks: pebbles / leaves / straw of the material, each its own shade, and a few four times larger; where they
    // are smaller than the pixel, their mean share of the ground.
    for (uint k = 0u; k < 2u && m.specks > 0.0; ++k) {
        float size = m.speckSize * (k == 0u ? 1.0 : 4.0), share = m.specks * (k == 0u ? 1.0 : 0.4);
        float ws = octaveWeight(size, footprint);
        vec3 s = ws > 0.0 ? speckAt(xy, size, share, footprint, 40u + 8u * k) : vec3(0.0);
        vec3 tint = vec3(1.0);
        if (ws > 0.0) { // each speck its own value and hue: grey stone, rusty, olive bits of plant
            vec2 hs = vec2(valueNoise(xy, size * 2.0, 41u + 8u * k), valueNoise(xy, size * 3.0, 42u + 8u * k)) - 0.5;
            tint = (1.0 + 0.5 * hs.x) * (vec3(1.0) + m.hueJitter * vec3(0.5 * hs.y, 0.3 * abs(hs.y), -0.6 * hs.y));
        }
        albedo = mix(albedo, m.speck * tint, ws * s.x + (1.0 - ws) * share);
        slope += ws * s.yz * 0.8;
    }
    return GroundSample(albedo, slope);
}

// The direction of d as a number in [0, 4) that grows with its angle (a quarter turn per unit), from + - * / alone:
// enough to lay stripes around a point, and the same on every device (no atan).
float diamondAngle(vec2 d) {
    float s = abs(d.x) + abs(d.y);
    if (s <= 0.0) return 0.0;
    float q = d.y / s;
    return d.x >= 0.0 ? (d.y >= 0.0 ? q : 4.0 + q) : 2.0 - q;
}

// Blades lying in a direction hashed per 12 cm cell (thatch is tangled): 1 on a blade, 0 in the gaps between, for
// blades `width` x `length` metres. Cells are independent, so blades end at their borders as broken ones do.
float lyingBlades(vec2 xy, float width, float length, uint salt) {
    ivec2 c = ivec2(floor(xy / 0.12));
    vec2 dir = vec2(latticeHash(c, salt), latticeHash(c, salt + 1u)) - 0.5;
    dir = dot(dir, dir) > 1e-4 ? normalize(dir) : vec2(1.0, 0.0);
    vec2 q = vec2(dot(xy, dir), dot(xy, vec2(-dir.y, dir.x))) / vec2(length, width);
    return smoothstep(0.48, 0.72, valueNoise(q, 1.0, salt + 2u));
}

// The ground under the plants (turf, issue 46 "under the plants"): a mat of low clumps, live and dry, with dark
// gaps between them, blades lying over them, moss in the hollows and soil showing through in specks, around `cover`
// (the linear albedo of the plants above, cover map). Each layer fades to its mean as it shrinks below the pixel, so
// from afar the turf is the cover's shaded mean colour and up close it has the grain of a real sward's base.
GroundSample turfGround(vec3 cover, vec3 soil, vec2 xy, float footprint) {
    const vec3 straw = vec3(0.24, 0.20, 0.12), dead = vec3(0.11, 0.085, 0.055);
    float dry = smoothstep(0.3, 0.9, valueNoise(xy, 1.1, 50u) * 0.7 + valueNoise(xy, 0.25, 51u) * 0.3);
    vec3 gap = mix(cover * 0.2, soil * 0.5, 0.5);
    vec3 mean = mix(mix(cover * 0.55, straw * 0.8, 0.2 + 0.4 * dry), gap, 0.3);
    vec2 slope = vec2(0.0);
    // Clumps of about 9 cm, each live, yellowing, straw or dead by its own hash and the patch's dryness.
    float wClump = octaveWeight(0.045, footprint);
    vec3 albedo = mean;
    if (wClump > 0.0) {
        vec2 toCentre;
        vec2 warped = xy + 0.04 * (vec2(valueNoise(xy, 0.12, 55u), valueNoise(xy, 0.12, 56u)) - 0.5);
        vec4 clump = clodAt(warped, 0.09, 57u, toCentre);
        float kind = clamp(clump.z + 0.6 * (dry - 0.5), 0.0, 1.0);
        vec3 own = kind < 0.45 ? cover * (0.6 + 0.5 * clump.z) : kind < 0.75 ? mix(cover, straw, 0.5) : kind < 0.92 ? straw : dead;
        // Its blades radiate from its centre: stripes around it, a dozen or so, broken along their length.
        float angle = diamondAngle(toCentre), radius = length(toCentre);
        float blades = valueNoise(vec2(angle * 3.6 + 17.0 * clump.z, radius * 30.0), 1.0, 58u);
        own *= 0.55 + 0.9 * smoothstep(0.3, 0.7, blades) * octaveWeight(0.012, footprint) +
               0.45 * (1.0 - octaveWeight(0.012, footprint));
        vec3 clumpColour = mix(gap, own, smoothstep(0.0, 0.35, clump.x));
        albedo = mix(mean, clumpColour, wClump);
        slope -= wClump * 0.5 * toCentre / 0.09;
    }
    // Blades lying over the clumps (2 x 12 cm, then 6 mm x 5 cm): lit blades and their shadows.
    float wCoarse = octaveWeight(0.02, footprint), wFine = octaveWeight(0.006, footprint);
    if (wCoarse > 0.0) albedo *= 1.0 + wCoarse * 0.7 * (lyingBlades(xy, 0.02, 0.12, 60u) - 0.35);
    if (wFine > 0.0) albedo *= 1.0 + wFine * 0.6 * (lyingBlades(xy + 0.37, 0.006, 0.05, 70u) - 0.35);
    // Moss in damp hollows, soil showing through in specks.
    float moss = smoothstep(0.62, 0.8, valueNoise(xy, 0.45, 53u)) * 0.5;
    albedo = mix(albedo, vec3(0.045, 0.07, 0.025), moss);
    float wSpeck = octaveWeight(0.012, footprint);
    if (wSpeck > 0.0) albedo = mix(albedo, soil, wSpeck * speckAt(xy, 0.012, 0.04, footprint, 54u).x);
    return GroundSample(albedo, slope);
}

// The shading normal of geometric normal n tilted by a bump slope (small slopes: the height field's normal).
vec3 bumpedNormal(vec3 n, vec2 slope) { return normalize(n - vec3(slope, 0.0) * n.z); }

#endif
