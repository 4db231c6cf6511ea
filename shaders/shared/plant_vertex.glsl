// Quad geometry of one expanded plant: shared by the draw vertex shader (plant.vert) and the bake pass
// (plant_bake.comp) that writes the same vertices into a static buffer for benchmarks and CPU-reference tests.
// The instance's level of detail fixes the quad set: near 4 quads (two crossed vertical ones and two tilted
// ones, dense from above too), mid 2 crossed vertical quads, far 1 billboard turned towards the camera about the
// plant's up axis. Needs vegetation.glsl (its constants) first; declares the atlas cell table.
#ifndef SWARD_PLANT_VERTEX_GLSL
#define SWARD_PLANT_VERTEX_GLSL

layout(set = 0, binding = kBindingAtlasCells, std430) readonly buffer Cells { AtlasCellGpu cells[]; };

// (angle offset about up, tilt away from vertical) per quad, radians. Near: two upright crossed quads and two
// leaning ones; mid: two crossed quads leaning apart. The lean is what covers the ground seen from above.
const vec2 kNearQuads[4] = vec2[](vec2(0.0, 0.0), vec2(1.5707963, 0.0), vec2(0.7853982, 0.95), vec2(3.9269908, 0.95));
const vec2 kMidQuads[2] = vec2[](vec2(0.0, 0.6), vec2(4.712389, 0.6));
// The whole quad's corners (x across: 0 left, 1 right; y up: 0 bottom, 1 top), drawn as the fan (1, 2, 0), (2, 3, 0)
// (fanCorner); a cut plant in a cut-out draw repeats corner 3 for its fan's further, empty triangles.
const vec2 kFullQuadFan[4] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 1));

struct PlantVertex {
    vec3 position;        // world, metres
    vec2 uv;              // cell coordinates (u across, v down, 0..1 the cell; u runs to PlantQuad::repeat)
    float heightFraction; // 0 at the base, 1 at the top of the (uncut) plant
    float random;         // the plant's random value
};

// Corner i of cell `cell`'s cut-out polygon, in cell uv (u right, v down).
vec2 cutoutCorner(uint cell, uint i) {
    vec4 pair = cells[cell].cutout[i >> 1];
    return (i & 1u) == 0u ? pair.xy : pair.zw;
}

// The quad of one plant in one LOD: its frame, size and bend, so that any point of its cell can be placed on it.
struct PlantQuad {
    vec3 base, side, rise, up;
    float height, width, cutFraction, random;
    vec2 tip;
    vec3 baseAspect; // the cell's base u, base v, aspect
    vec4 uvRect;
    float opacity; // merged in depth: the card's alpha a shows as 1 - (1 - a)^opacity (plantTexel); else 1
    float repeat; // copies of the plant side by side across the quad: a merged far billboard's widening, else 1
};

// Quad `quad` of `quads` of a felled plant (gpu_layout.h, kFelledLean): across the lay direction (the push that
// felled it, `tip`), fanned evenly over +-kFelledSpread, leaning kFelledLean towards the tip; the lean is its whole
// bend. Mirrored by vegetation/expansion_reference.cpp.
PlantQuad felledQuad(PlantQuad q, vec2 tip, float orientation, uint quads, uint quad) {
    vec2 lay = dot(tip, tip) > 1e-8 ? normalize(tip) : vec2(cos(orientation), sin(orientation));
    float spread = kFelledSpread * (2.0 * float(quad) / float(quads - 1u) - 1.0);
    vec3 horizontal = vec3(-lay.y, lay.x, 0.0) * cos(spread) + vec3(lay, 0.0) * sin(spread);
    q.side = normalize(horizontal - q.up * dot(horizontal, q.up));
    vec3 along = cross(q.side, q.up); // towards +lay
    q.rise = normalize(q.up * cos(kFelledLean) + along * sin(kFelledLean));
    q.tip = vec2(0.0);
    return q;
}

// `cell` returns the plant's atlas cell (an index: reading the whole cell with its polygon per vertex is a cost).
// `camera`: the reference camera's position, which far billboards face.
PlantQuad plantQuad(ExpandedPlant instance, uint lod, uint quad, vec3 camera, out uint cell) {
    PlantQuad q;
    q.base = instance.positionHeight.xyz;
    q.height = instance.positionHeight.w;
    q.up = octahedralDecode(instance.up);
    uint category = bitfieldExtract(instance.attributes, 0, 2);
    uint variant = bitfieldExtract(instance.attributes, 2, 6) % max(veg.atlasColumns[category], 1u);
    float orientation = float(bitfieldExtract(instance.attributes, 8, 8)) * (6.2831853 / 256.0);
    q.random = float(bitfieldExtract(instance.attributes, 16, 8)) * (1.0 / 255.0);
    cell = category * veg.counts.w + variant;
    vec4 baseAspect = cells[cell].baseAspect;
    float widen = float(bitfieldExtract(instance.fade, 8, 8)) / kWidthScaleUnit; // far merging (mergeWidthScale)
    q.width = q.height * baseAspect.z * widen;
    q.repeat = max(widen, 1.0);
    // Far merging in depth (depthMergeScale in gpu_layout.h): the card's opacity exponent, exactly 1 where not merged.
    float depthScale = lod == kLodFar ? float(bitfieldExtract(instance.attributes, 8, 8)) / kWidthScaleUnit : 1.0;
    q.opacity = depthScale == 1.0 ? 1.0 : pow(depthScale, kDepthMergeExponent);
    q.baseAspect = baseAspect.xyz;
    q.uvRect = cells[cell].uvRect;
    q.cutFraction = float(instance.fade >> 24) * (1.0 / 255.0); // height is already cut to this fraction

    if (lod == kLodFar) {
        // Faces the camera: upright when seen from the side, lying towards the camera when seen from above.
        vec3 toCamera = normalize(camera - q.base);
        q.side = cross(q.up, toCamera);
        // Seen from straight above, any side will do: the plant's random value picks one (a far billboard's bits
        // 8-15 hold its depth merging, not an orientation).
        if (dot(q.side, q.side) < 1e-4) q.side = vec3(cos(6.2831853 * q.random), sin(6.2831853 * q.random), 0.0);
        q.side = normalize(q.side);
        q.rise = normalize(cross(toCamera, q.side));
    } else if (bitfieldExtract(instance.fade, 17, 4) == kPlantStateFelled) {
        return felledQuad(q, unpackHalf2x16(instance.tip), orientation, lod == kLodNear ? 4u : 2u, quad);
    } else {
        vec2 angleTilt = lod == kLodNear ? kNearQuads[quad] : kMidQuads[quad];
        float angle = orientation + angleTilt.x;
        vec3 horizontal = vec3(cos(angle), sin(angle), 0.0);
        q.side = normalize(horizontal - q.up * dot(horizontal, q.up));
        vec3 normal = cross(q.side, q.up);
        q.rise = normalize(q.up * cos(angleTilt.y) + normal * sin(angleTilt.y));
    }
    q.tip = unpackHalf2x16(instance.tip);
    return q;
}

// The point of the quad at corner (x across, y up, 0..1), bent. The bend grows with the square of the height
// fraction, so only the quad's corners lie on the bent blade; its edges are straight.
vec3 quadPoint(PlantQuad q, vec2 corner, out float fraction) {
    // Cell v runs downwards; the plant base sits at (baseU, baseV) of the cell.
    float cellV = 1.0 - corner.y;
    float along = (q.baseAspect.y - cellV) * q.height;
    fraction = q.baseAspect.y > 0.0 ? along / (q.baseAspect.y * max(q.height, 1e-6)) : 0.0;
    vec3 position = q.base + q.side * (q.width * (corner.x - q.baseAspect.x)) + q.rise * along;

    // Bend: the tip moves by tip * height horizontally and drops so the blade keeps its length; lower
    // vertices follow quadratically (a cantilever bends most near the tip).
    float bend = fraction * fraction;
    float drop = q.height * (1.0 - sqrt(max(1.0 - dot(q.tip, q.tip), 0.0)));
    position += vec3(q.tip * q.height, 0.0) * bend - q.up * (drop * bend);
    return position;
}

// Corner height (quadPoint's y: 0 the cell's bottom edge, 1 its top) of the far slicing's cut: where the plant rises
// attributes bits 24-31 / kSliceUnit of its height above its base (the base sits at cell v = baseV).
float sliceBottom(ExpandedPlant instance, PlantQuad q) {
    float cut = float(bitfieldExtract(instance.attributes, 24, 8)) * (1.0 / kSliceUnit);
    return cut > 0.0 ? clamp(1.0 - q.baseAspect.y + cut, 0.0, 1.0) : 0.0;
}

// Corner `corner` (0 .. quadCornerCount - 1) of the instance's quad `q` (plantQuad; its atlas cell is `cell`):
// callers that need several vertices of one quad build the quad once.
PlantVertex quadCorner(ExpandedPlant instance, PlantQuad q, uint cell, uint lod, uint corner) {
    const bool cutout = veg.options.x >= 3u && lod != kLodFar;
    float fraction;
    if (!cutout) {
        vec2 at = kFullQuadFan[corner];
        // Far slicing (sliceHeight): the quad starts at the cut height, so its bottom rows of the cell are not drawn.
        at.y = mix(sliceBottom(instance, q), 1.0, at.y);
        vec3 position = quadPoint(q, at, fraction);
        // Cut plants show the lower part of the texture (stalks), not a squashed plant. A merged billboard shows
        // `repeat` copies of its plant side by side (plantTexel), not one plant stretched.
        float u = at.x * q.repeat;
        if (q.random > 0.5) u = q.repeat - u; // mirror half of the plants for variety
        float v = 1.0 - at.y * q.cutFraction;
        return PlantVertex(position, vec2(u, v), fraction, q.random);
    }
    // Cut-out: corner (x across, y up) of a point of the cell's polygon; cut plants, which stretch the lower part of
    // their texture over the quad, keep the whole quad (a fan of two triangles and empty ones).
    vec2 at, uv;
    if ((instance.fade >> 24) == 255u) {
        uv = cutoutCorner(cell, corner);
        at = vec2((q.random > 0.5) ? 1.0 - uv.x : uv.x, 1.0 - uv.y);
    } else {
        at = kFullQuadFan[min(corner, 3u)];
        uv = vec2((q.random > 0.5) ? 1.0 - at.x : at.x, 1.0 - at.y * q.cutFraction);
    }
    // On the quad's plane between its bottom and top edges: exactly where the whole quad shows that texel.
    float bottomFraction, topFraction;
    vec3 bottom = quadPoint(q, vec2(at.x, 0.0), bottomFraction), top = quadPoint(q, vec2(at.x, 1.0), topFraction);
    return PlantVertex(mix(bottom, top, at.y), uv, mix(bottomFraction, topFraction, at.y), q.random);
}

// Corner `index` of the instance's indexed draw (corner index % quadCornerCount of quad index / quadCornerCount,
// plantIndex): the draws' vertex shader's gl_VertexIndex.
PlantVertex plantCorner(ExpandedPlant instance, uint lod, uint index, vec3 camera) {
    uint cell, perQuad = quadCornerCount(lod, veg.options.x);
    PlantQuad q = plantQuad(instance, lod, index / perQuad, camera, cell);
    return quadCorner(instance, q, cell, lod, index % perQuad);
}

#endif
