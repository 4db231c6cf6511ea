#include "vegetation/expansion_reference.h"

#include "vegetation/records.h"

#include "shared/plant_blades.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

constexpr uint32_t kNoLod = 0xffffffffu;

struct LodChoice {
    uint32_t lodA = kNoLod, lodB = kNoLod;
    float t = 0.0f;
};

LodChoice chooseLod(const LodParams& lod, float distance) {
    float band = std::max(lod.band, 1e-3f), half = 0.5f * band;
    float d0 = lod.nearToMid, d1 = lod.midToFar, d2 = lod.farLimit;
    if (distance >= d2 + half) return {};
    if (distance < d0 - half) return {gpu::kLodNear, kNoLod, 0.0f};
    if (distance < d0 + half) return {gpu::kLodNear, gpu::kLodMid, (distance - (d0 - half)) / band};
    if (distance < d1 - half) return {gpu::kLodMid, kNoLod, 0.0f};
    if (distance < d1 + half) return {gpu::kLodMid, gpu::kLodFar, (distance - (d1 - half)) / band};
    if (distance < d2 - half) return {gpu::kLodFar, kNoLod, 0.0f};
    return {gpu::kLodFar, kNoLod, (distance - (d2 - half)) / band};
}

bool clusterVisible(const std::array<glm::vec4, 5>& planes, const LodParams& lod, glm::vec3 camera, glm::vec3 lo,
                    glm::vec3 hi) {
    for (const glm::vec4& plane : planes) {
        glm::vec3 farthest(plane.x > 0 ? hi.x : lo.x, plane.y > 0 ? hi.y : lo.y, plane.z > 0 ? hi.z : lo.z);
        if (glm::dot(glm::vec3(plane), farthest) + plane.w < 0.0f) return false;
    }
    glm::vec3 nearest = glm::clamp(camera, lo, hi);
    return glm::distance(nearest, camera) < lod.farLimit + 0.5f * lod.band;
}

glm::vec2 windTip(const WindParams& wind, glm::vec3 position, float random, float time) {
    glm::vec2 dir = wind.direction();
    float phase = random * 6.2831853f;
    float speed = 0.8f + 0.4f * random;
    float sway = std::sin(time * 2.1f * speed + phase + glm::dot(glm::vec2(position), glm::vec2(0.21f, 0.13f)));
    float travel = glm::dot(glm::vec2(position), dir) / std::max(wind.gustWavelength, 1.0f);
    float wave = std::max(std::sin(6.2831853f * (wind.gustFrequency * time - travel)), 0.0f);
    float gust = wind.gustStrength * wave * wave;
    float flutter = wind.flutter * std::sin(time * 6.3f * speed + phase * 3.0f);
    return dir * (wind.strength * (0.8f + 0.2f * sway) + gust) + glm::vec2(-dir.y, dir.x) * flutter;
}

// A plant's height after its size and cut (vegetation_expand.comp's plantHeight).
float plantHeight(const VegetationParams& vegetation, const gpu::PlantStatic& plant, const gpu::PlantDynamic& dynamic) {
    PlantInstance decoded = decodePlantStatic(plant);
    PlantMotion motion = decodePlantDynamic(dynamic);
    float cut = motion.state == gpu::kPlantStateCut ? motion.cutFraction : 1.0f;
    return vegetation.categories[decoded.category].height * (float(decoded.size) / gpu::kPlantSizeDivisor) * cut;
}

// clusterCardCover(): sliceHeight's cover2 and cover1 of the cluster, summed in plant order.
glm::vec2 clusterCardCover(const VegetationParams& vegetation, const FieldVegetation& field,
                           const gpu::PlantCluster& box, const std::array<float, 4>& categoryCard) {
    glm::vec2 sums(0.0f);
    for (uint32_t i = box.range.x; i < box.range.x + box.range.y; ++i) {
        float h = plantHeight(vegetation, field.staticRecords[i], field.dynamicRecords[i]);
        sums += categoryCard[field.staticRecords[i].attributes & 3u] * glm::vec2(h * h, h);
    }
    float fieldSize = field.positionStep * float(gpu::kPlantPositionSteps);
    return sums / (fieldSize * fieldSize / float(field.clusters.size()));
}

} // namespace

gpu::ExpandedPlant expandWholePlant(const VegetationParams& vegetation, const WindParams& wind,
                                    const FieldVegetation& field, uint32_t i, const gpu::PlantDynamic& dynamic,
                                    double time) {
    const gpu::PlantStatic& plant = field.staticRecords[i];
    const glm::vec3 position = decodePlantPosition(plant, field.origin, field.positionStep);
    const PlantInstance decoded = decodePlantStatic(plant);
    const PlantMotion motion = decodePlantDynamic(dynamic);
    const float random = float(decoded.random) / 255.0f;
    glm::vec2 tip = motion.bend + windTip(wind, position, random, float(time));
    const float len = glm::length(tip);
    if (len > gpu::kMaxTipOffset) tip *= gpu::kMaxTipOffset / len;
    const uint32_t cutByte = (dynamic.state >> 24) & 0xffu;
    const uint32_t fade = (uint32_t(gpu::kWidthScaleUnit) << 8) | (motion.state << 17) | (cutByte << 24);
    return {glm::vec4(position, plantHeight(vegetation, plant, dynamic)), plant.up, plant.attributes & 0x00ffffffu,
            glm::packHalf2x16(tip), fade};
}

ReferenceExpansion referenceExpand(const VegetationTile& tile, const VegetationParams& vegetation, const LodParams& lod,
                                   const WindParams& wind, const Camera& camera, double time,
                                   const ExpansionAtlas& atlas) {
    ReferenceExpansion out;
    const auto planes = camera.frustumPlanes();
    const glm::vec3 eye(camera.position);
    // Each field's first plant in the tile's record buffers (fields packed in order).
    std::vector<uint32_t> fieldFirsts(1, 0u);
    for (const FieldVegetation& field : tile.fields) fieldFirsts.push_back(fieldFirsts.back() + field.plantCount());
    const uint32_t perField = tile.clustersPerField * tile.clustersPerField;
    std::vector<uint32_t> order;
    frontToBack(clusterBoxes(tile), eye, order);
    for (uint32_t cluster : order) {
        const FieldVegetation& field = tile.fields[cluster / perField];
        const gpu::PlantCluster& box = field.clusters[cluster % perField];
        const uint32_t fieldFirst = fieldFirsts[cluster / perField];
        if (box.range.y == 0 || !clusterVisible(planes, lod, eye, glm::vec3(box.boundsMin), glm::vec3(box.boundsMax)))
            continue;
        ++out.visibleClusters;
        out.plantsConsidered += box.range.y;
        glm::vec2 cover(-1.0f);
        const bool backwards =
            gpu::walkPlantsBackwards(eye.x, eye.y, box.boundsMin.x, box.boundsMin.y, box.boundsMax.x, box.boundsMax.y);
        for (uint32_t k = 0; k < box.range.y; ++k) {
            const uint32_t i = box.range.x + (backwards ? box.range.y - 1 - k : k);
            const gpu::PlantStatic& plant = field.staticRecords[i];
            glm::vec3 position = decodePlantPosition(plant, field.origin, field.positionStep);
            const float distance = glm::distance(position, eye);
            LodChoice choice = chooseLod(lod, distance);
            if (choice.lodA == kNoLod) continue;
            float height = plantHeight(vegetation, plant, field.dynamicRecords[i]);
            uint32_t width = uint32_t(gpu::kWidthScaleUnit), depth = width; // widthBits(), depthBits()
            const bool farAlone = choice.lodA == gpu::kLodFar && choice.lodB == kNoLod;
            // viewSine(): how grazing the view is, for depth merging and slicing
            const float sinView =
                farAlone ? glm::dot(glm::normalize(eye - position), decodeOctahedral(plant.up)) : 0.0f;
            if (farAlone) {
                float widthPixels =
                    height * atlas.aspect[plant.attributes & 3u] * float(camera.fy) / std::max(distance, 1e-3f);
                width =
                    gpu::scaleBits(gpu::mergeWidthScale(lod.mergeWidth, widthPixels, gpu::mergeHash(fieldFirst + i)));
                const float heightPixels = height * float(camera.fy) / std::max(distance, 1e-3f);
                depth = gpu::scaleBits(
                    gpu::depthMergeScale(lod.depthMerge, heightPixels, sinView, gpu::depthMergeHash(fieldFirst + i)));
                if (width == 0 || depth == 0) continue;
            }
            uint32_t slice = 0; // sliceBits()
            if (farAlone && lod.sliceLayers > 0.0f) {
                if (cover.x < 0.0f) cover = clusterCardCover(vegetation, field, box, atlas.card);
                float cut = gpu::sliceHeight(lod.sliceLayers, cover.x, cover.y, sinView);
                slice = uint32_t(std::min(cut / std::max(height, 1e-6f), 1.0f) * gpu::kSliceUnit);
                if (slice == uint32_t(gpu::kSliceUnit)) continue;
            }
            gpu::ExpandedPlant expanded = expandWholePlant(vegetation, wind, field, i, field.dynamicRecords[i], time);
            expanded.attributes |= slice << 24;
            expanded.fade = uint32_t(std::clamp(choice.t, 0.0f, 1.0f) * 255.0f + 0.5f) | (width << 8) |
                            (expanded.fade & 0xffff0000u);
            const uint32_t fade = expanded.fade;
            // A far billboard's bits 8-15 hold its depth merging (vegetation_expand.comp), not an orientation.
            auto withDepth = [depth](uint32_t attributes) { return (attributes & ~0xff00u) | (depth << 8); };
            if (choice.lodA == gpu::kLodFar) expanded.attributes = withDepth(expanded.attributes);
            out.lods[choice.lodA].push_back(expanded);
            if (choice.lodB != kNoLod) {
                expanded.fade = fade | 0x10000u;
                if (choice.lodB == gpu::kLodFar) expanded.attributes = withDepth(expanded.attributes);
                out.lods[choice.lodB].push_back(expanded);
            }
        }
    }
    return out;
}

float plantRandom(const gpu::ExpandedPlant& plant) {
    return float((plant.attributes >> 16) & 0xffu) * (1.0f / 255.0f);
}

namespace {

// One quad of a plant (plant_vertex.glsl's PlantQuad): frame, size and bend.
struct ReferenceQuad {
    glm::vec3 base, side, rise, up;
    float height, width;
    glm::vec2 tip;
    glm::vec3 baseAspect;

    // quadPoint() before its bend: the point at corner (x across, y up) and its bend weight (fraction^2).
    glm::vec3 unbent(glm::vec2 corner, float& bend) const {
        float cellV = 1.0f - corner.y;
        float along = (baseAspect.y - cellV) * height;
        float fraction = baseAspect.y > 0.0f ? along / (baseAspect.y * std::max(height, 1e-6f)) : 0.0f;
        bend = fraction * fraction;
        return base + side * (width * (corner.x - baseAspect.x)) + rise * along;
    }
    // quadPoint(): the bent point at corner (x across, y up).
    glm::vec3 point(glm::vec2 corner) const {
        float bend;
        const glm::vec3 position = unbent(corner, bend);
        return bentPoint(position, bend, tip, height, up);
    }
};

ReferenceQuad referenceQuad(const gpu::ExpandedPlant& plant, uint32_t lod, uint32_t quad, glm::vec3 cameraPosition,
                            glm::vec3 cellBaseAspect) {
    static const glm::vec2 nearQuads[4] = {{0.0f, 0.0f}, {1.5707963f, 0.0f}, {0.7853982f, 0.95f}, {3.9269908f, 0.95f}};
    static const glm::vec2 midQuads[2] = {{0.0f, 0.6f}, {4.712389f, 0.6f}};
    ReferenceQuad q;
    q.base = glm::vec3(plant.positionHeight);
    q.height = plant.positionHeight.w;
    q.up = decodeOctahedral(plant.up);
    q.width = q.height * cellBaseAspect.z * (float((plant.fade >> 8) & 0xffu) / gpu::kWidthScaleUnit);
    q.tip = glm::unpackHalf2x16(plant.tip);
    q.baseAspect = cellBaseAspect;
    float orientation = float((plant.attributes >> 8) & 0xffu) * (6.2831853f / 256.0f);
    if (lod == gpu::kLodFar) {
        glm::vec3 toCamera = glm::normalize(cameraPosition - q.base);
        q.side = glm::cross(q.up, toCamera);
        if (glm::dot(q.side, q.side) < 1e-4f) { // plant_vertex.glsl: the plant's random value picks a side
            const float turn = 6.2831853f * plantRandom(plant);
            q.side = glm::vec3(std::cos(turn), std::sin(turn), 0.0f);
        }
        q.side = glm::normalize(q.side);
        q.rise = glm::normalize(glm::cross(toCamera, q.side));
    } else if (((plant.fade >> 17) & 0xfu) == gpu::kPlantStateFelled) {
        // plant_vertex.glsl's felledQuad: across the lay direction, fanned, leaning kFelledLean along it.
        const uint32_t quads = lod == gpu::kLodNear ? gpu::kQuadsNear : gpu::kQuadsMid;
        glm::vec2 lay = glm::dot(q.tip, q.tip) > 1e-8f ? glm::normalize(q.tip)
                                                       : glm::vec2(std::cos(orientation), std::sin(orientation));
        float spread = gpu::kFelledSpread * (2.0f * float(quad) / float(quads - 1u) - 1.0f);
        glm::vec3 horizontal = glm::vec3(-lay.y, lay.x, 0.0f) * std::cos(spread) + glm::vec3(lay, 0.0f) * std::sin(spread);
        q.side = glm::normalize(horizontal - q.up * glm::dot(horizontal, q.up));
        q.rise = glm::normalize(q.up * std::cos(gpu::kFelledLean) + glm::cross(q.side, q.up) * std::sin(gpu::kFelledLean));
        q.tip = glm::vec2(0.0f);
    } else {
        glm::vec2 angleTilt = lod == gpu::kLodNear ? nearQuads[quad] : midQuads[quad];
        float angle = orientation + angleTilt.x;
        glm::vec3 horizontal(std::cos(angle), std::sin(angle), 0.0f);
        q.side = glm::normalize(horizontal - q.up * glm::dot(horizontal, q.up));
        glm::vec3 normal = glm::cross(q.side, q.up);
        q.rise = glm::normalize(q.up * std::cos(angleTilt.y) + normal * std::sin(angleTilt.y));
    }
    return q;
}

// Corner (x across, y up) of cut-out fan vertex k (plant_vertex.glsl: fanCorner, cutoutCorner, kFullQuadFan).
glm::vec2 cutoutFanCorner(const gpu::ExpandedPlant& plant, const CutoutPolygon& cutout, uint32_t k) {
    static const glm::vec2 fullQuad[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const uint32_t corner = gpu::fanCorner(k);
    if ((plant.fade >> 24) != 255u) return fullQuad[std::min(corner, 3u)];
    const glm::vec2 uv = cutout.corners[corner];
    return {plantRandom(plant) > 0.5f ? 1.0f - uv.x : uv.x, 1.0f - uv.y};
}

} // namespace

glm::vec3 bentPoint(glm::vec3 unbent, float bend, glm::vec2 tip, float height, glm::vec3 up) {
    float drop = height * (1.0f - std::sqrt(std::max(1.0f - glm::dot(tip, tip), 0.0f)));
    return unbent + glm::vec3(tip * height, 0.0f) * bend - up * (drop * bend);
}

void unbentQuadCorners(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cellBaseAspect, glm::vec3* corners,
                       float* bends) {
    static const glm::vec2 quadCorners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const uint32_t quads = gpu::plantVertexCount(lod, 0u) / gpu::kVerticesPerQuad;
    for (uint32_t quad = 0; quad < quads; ++quad) {
        const ReferenceQuad q = referenceQuad(plant, lod, quad, glm::vec3(0.0f), cellBaseAspect);
        for (uint32_t k = 0; k < 4; ++k) corners[4 * quad + k] = q.unbent(quadCorners[k], bends[4 * quad + k]);
    }
}

void plantQuadCorners(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cameraPosition, glm::vec3 cellBaseAspect,
                      glm::vec3* corners) {
    static const glm::vec2 quadCorners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const uint32_t quads = gpu::plantVertexCount(lod, 0u) / gpu::kVerticesPerQuad;
    for (uint32_t quad = 0; quad < quads; ++quad) {
        const ReferenceQuad q = referenceQuad(plant, lod, quad, cameraPosition, cellBaseAspect);
        for (uint32_t k = 0; k < 4; ++k) corners[4 * quad + k] = q.point(quadCorners[k]);
    }
}

std::vector<glm::vec3> referencePlantVertices(const gpu::ExpandedPlant& plant, uint32_t lod, glm::vec3 cameraPosition,
                                              glm::vec3 cellBaseAspect, const CutoutPolygon* cutout,
                                              uint32_t cutoutCorners) {
    static const glm::vec2 fullQuad[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}; // kFullQuadFan
    const bool fan = cutout && cutoutCorners >= 4 && lod != gpu::kLodFar;
    const uint32_t perQuad = gpu::quadVertexCount(lod, fan ? cutoutCorners : 0u);
    std::vector<glm::vec3> vertices;
    for (uint32_t v = 0; v < gpu::plantVertexCount(lod, fan ? cutoutCorners : 0u); ++v) {
        const ReferenceQuad q = referenceQuad(plant, lod, v / perQuad, cameraPosition, cellBaseAspect);
        if (!fan) {
            // plant_vertex.glsl's sliceBottom: a sliced far billboard starts at its cut height.
            const float cut = float(plant.attributes >> 24) * (1.0f / gpu::kSliceUnit);
            const float bottom = cut > 0.0f ? std::clamp(1.0f - cellBaseAspect.y + cut, 0.0f, 1.0f) : 0.0f;
            const glm::vec2 corner = fullQuad[gpu::fanCorner(v % perQuad)];
            vertices.push_back(q.point({corner.x, bottom + (1.0f - bottom) * corner.y}));
            continue;
        }
        // Between the quad's bottom and top edges, as the shader places a polygon corner.
        const glm::vec2 at = cutoutFanCorner(plant, *cutout, v % perQuad);
        vertices.push_back(glm::mix(q.point({at.x, 0.0f}), q.point({at.x, 1.0f}), at.y));
    }
    return vertices;
}

std::vector<glm::vec3> referenceBladeVertices(const gpu::ExpandedPlant& plant, uint32_t blades, float aspect) {
    // plant_blades.glsl's bladePlant.
    const glm::vec3 base(plant.positionHeight), up = decodeOctahedral(plant.up);
    const float height = plant.positionHeight.w;
    const float cardWidth = height * aspect * (float((plant.fade >> 8) & 0xffu) / gpu::kWidthScaleUnit);
    const float orientation = float((plant.attributes >> 8) & 0xffu) * (6.2831853f / 256.0f);
    const float widthScale = 1.0f - float(plant.fade & 0xffu) * (1.0f / 255.0f);
    const bool felled = ((plant.fade >> 17) & 0xfu) == gpu::kPlantStateFelled;
    const glm::vec2 layTip = glm::unpackHalf2x16(plant.tip), tip = felled ? glm::vec2(0.0f) : layTip;
    const uint32_t key = gpu::bladeKey(plant.attributes, plant.up);
    std::vector<glm::vec3> vertices;
    vertices.reserve(blades * gpu::kBladeIndices);
    for (uint32_t blade = 0; blade < blades; ++blade) {
        const gpu::BladeShape s = gpu::bladeShape(base, up, height, cardWidth, orientation, key, blade, blades, felled,
                                                  layTip);
        glm::vec3 points[gpu::kBladeVertices];
        for (uint32_t j = 0; j < gpu::kBladeVertices; ++j)
            points[j] = gpu::bladePoint(s, j / 2, j & 1u, widthScale, height, up, tip);
        for (uint32_t k = blade * gpu::kBladeIndices; k < (blade + 1) * gpu::kBladeIndices; ++k)
            vertices.push_back(points[gpu::bladeIndex(k) % gpu::kBladeVertices]);
    }
    return vertices;
}

} // namespace sward
