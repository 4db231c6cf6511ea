// Blade geometry of an expanded near plant (plant_blades.h) for the blade draws (plant_blade.vert) and the bake
// (plant_bake.comp): the plant record decoded once, then any of its blades' vertices. Needs vegetation.glsl and
// plant_vertex.glsl (its atlas cell table) first.
#ifndef SWARD_PLANT_BLADES_GLSL
#define SWARD_PLANT_BLADES_GLSL

#include "plant_blades.h"

// Whether the near LOD draws `instance` as blades: VegetationConstants::options.y blades per plant of the categories
// in the mask options.z (the grass categories); the near cards' draw leaves these plants out.
bool drawnAsBlades(ExpandedPlant instance) {
    return veg.options.y > 0u && ((veg.options.z >> bitfieldExtract(instance.attributes, 0, 2)) & 1u) != 0u;
}

// What every blade of one plant shares.
struct BladePlant {
    vec3 base, up;
    float height, cardWidth, orientation;
    float widthScale; // 1 - the LOD cross-fade's t: a receding near plant's blades thin out
    vec2 tip;         // the wind's and interaction's bend (0 for a felled plant, whose blades lie along layTip)
    vec2 layTip;
    uint key, blades, cell;
    bool felled;
};

BladePlant bladePlant(ExpandedPlant instance) {
    BladePlant p;
    p.base = instance.positionHeight.xyz;
    p.height = instance.positionHeight.w;
    p.up = octahedralDecode(instance.up);
    uint category = bitfieldExtract(instance.attributes, 0, 2);
    uint variant = bitfieldExtract(instance.attributes, 2, 6) % max(veg.atlasColumns[category], 1u);
    p.cell = category * veg.counts.w + variant;
    float widen = float(bitfieldExtract(instance.fade, 8, 8)) / kWidthScaleUnit;
    p.cardWidth = p.height * cells[p.cell].baseAspect.z * widen; // plantQuad's width
    p.orientation = float(bitfieldExtract(instance.attributes, 8, 8)) * (6.2831853 / 256.0);
    p.widthScale = 1.0 - float(instance.fade & 0xffu) * (1.0 / 255.0);
    p.felled = bitfieldExtract(instance.fade, 17, 4) == kPlantStateFelled;
    p.layTip = unpackHalf2x16(instance.tip);
    p.tip = p.felled ? vec2(0.0) : p.layTip;
    p.key = bladeKey(instance.attributes, instance.up);
    p.blades = veg.options.y;
    return p;
}

BladeShape plantBlade(BladePlant p, uint blade) {
    return bladeShape(p.base, p.up, p.height, p.cardWidth, p.orientation, p.key, blade, p.blades, p.felled, p.layTip);
}

struct BladeVertex {
    vec3 position;
    float heightFraction; // quadPoint's fraction: along the blade / the plant's height
    float along;          // 0 at the root, 1 at the tip
    vec3 normal;          // the unnormalised normal of the vertex's segment (both its triangles lie in one plane)
};

// Vertex `vertex` (blade vertex / kBladeVertices, its number in the blade as plant_blades.h orders them) of blade
// shape `s` of plant `p`.
BladeVertex bladeVertex(BladePlant p, BladeShape s, uint vertex) {
    uint j = vertex % kBladeVertices, level = j / 2u, edge = j & 1u;
    BladeVertex v;
    v.position = bladePoint(s, level, edge, p.widthScale, p.height, p.up, p.tip);
    v.heightFraction = bladeFraction(s, level, p.height);
    v.along = float(level) / float(kBladeSegments);
    // A blade's width runs along one direction (its side), so each segment is a planar trapezoid: its normal from its
    // first triangle's corners, (left, right, next left) of level min(level, segments - 1).
    uint l = min(level, kBladeSegments - 1u);
    vec3 a = bladePoint(s, l, 0u, p.widthScale, p.height, p.up, p.tip);
    vec3 b = bladePoint(s, l, 1u, p.widthScale, p.height, p.up, p.tip);
    vec3 c = bladePoint(s, l + 1u, 0u, p.widthScale, p.height, p.up, p.tip);
    v.normal = cross(b - a, c - a);
    return v;
}

#endif
