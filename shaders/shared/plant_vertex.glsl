// Quad geometry of one expanded plant: shared by the draw vertex shader (plant.vert) and the bake pass
// (plant_bake.comp) that writes the same vertices into a static buffer for benchmarks and CPU-reference tests.
// The instance's level of detail fixes the quad set: near 4 quads (two crossed vertical ones and two tilted
// ones, dense from above too), mid 2 crossed vertical quads, far 1 billboard turned towards the camera about the
// plant's up axis. Needs vegetation.glsl (its constants) first; declares the atlas cell table.
#ifndef SWARD_PLANT_VERTEX_GLSL
#define SWARD_PLANT_VERTEX_GLSL

layout(set = 0, binding = kBindingAtlasCells, std430) readonly buffer Cells { AtlasCellGpu cells[]; };

// Corners of the two triangles of a quad: x across (0 left, 1 right), y up (0 bottom, 1 top).
const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
// (angle offset about up, tilt away from vertical) per quad, radians. Near: two upright crossed quads and two
// leaning ones; mid: two crossed quads leaning apart. The lean is what covers the ground seen from above.
const vec2 kNearQuads[4] = vec2[](vec2(0.0, 0.0), vec2(1.5707963, 0.0), vec2(0.7853982, 0.95), vec2(3.9269908, 0.95));
const vec2 kMidQuads[2] = vec2[](vec2(0.0, 0.6), vec2(4.712389, 0.6));

struct PlantVertex {
    vec3 position;        // world, metres
    vec2 uv;              // atlas texture coordinates
    float heightFraction; // 0 at the base, 1 at the top of the (uncut) plant
    float random;         // the plant's random value
};

PlantVertex plantVertex(ExpandedPlant instance, uint lod, uint vertexIndex) {
    uint quad = vertexIndex / 6u;
    vec2 corner = kCorners[vertexIndex % 6u];

    vec3 base = instance.positionHeight.xyz;
    float height = instance.positionHeight.w;
    vec3 up = octahedralDecode(instance.up);
    uint category = bitfieldExtract(instance.attributes, 0, 2);
    uint variant = bitfieldExtract(instance.attributes, 2, 6) % max(veg.atlasColumns[category], 1u);
    float orientation = float(bitfieldExtract(instance.attributes, 8, 8)) * (6.2831853 / 256.0);
    float random = float(bitfieldExtract(instance.attributes, 16, 8)) * (1.0 / 255.0);
    AtlasCellGpu cell = cells[category * veg.counts.w + variant];
    float width = height * cell.baseAspect.z;

    vec3 side, rise;
    if (lod == kLodFar) {
        // Faces the camera: upright when seen from the side, lying towards the camera when seen from above.
        vec3 toCamera = normalize(veg.cameraPosition.xyz - base);
        side = cross(up, toCamera);
        if (dot(side, side) < 1e-4) side = vec3(cos(orientation), sin(orientation), 0.0);
        side = normalize(side);
        rise = normalize(cross(toCamera, side));
    } else {
        vec2 angleTilt = lod == kLodNear ? kNearQuads[quad] : kMidQuads[quad];
        float angle = orientation + angleTilt.x;
        vec3 horizontal = vec3(cos(angle), sin(angle), 0.0);
        side = normalize(horizontal - up * dot(horizontal, up));
        vec3 normal = cross(side, up);
        rise = normalize(up * cos(angleTilt.y) + normal * sin(angleTilt.y));
    }

    // Cell v runs downwards; the plant base sits at (baseU, baseV) of the cell.
    float cellV = 1.0 - corner.y;
    float cutFraction = float(instance.fade >> 24) * (1.0 / 255.0); // height is already cut to this fraction
    float along = (cell.baseAspect.y - cellV) * height;
    float fraction = cell.baseAspect.y > 0.0 ? along / (cell.baseAspect.y * max(height, 1e-6)) : 0.0;
    vec3 position = base + side * (width * (corner.x - cell.baseAspect.x)) + rise * along;

    // Bend: the tip moves by tip * height horizontally and drops so the blade keeps its length; lower
    // vertices follow quadratically (a cantilever bends most near the tip).
    vec2 tip = unpackHalf2x16(instance.tip);
    float bend = fraction * fraction;
    float drop = height * (1.0 - sqrt(max(1.0 - dot(tip, tip), 0.0)));
    position += vec3(tip * height, 0.0) * bend - up * (drop * bend);

    // Cut plants show the lower part of the texture (stalks), not a squashed plant.
    float u = (random > 0.5) ? 1.0 - corner.x : corner.x; // mirror half of the plants for variety
    float v = 1.0 - (1.0 - cellV) * cutFraction;
    return PlantVertex(position, mix(cell.uvRect.xy, cell.uvRect.zw, vec2(u, v)), fraction, random);
}

#endif
