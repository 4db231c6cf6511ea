#include "range/plant_quads.h"

#include "common/error.h"
#include "vegetation/atlas.h"
#include "vegetation/expansion_reference.h"
#include "vegetation/records.h"

#include <algorithm>

#include <cmath>
#include <glm/gtc/packing.hpp>
#include <limits>

namespace sward {

namespace {

// plant.vert's truth label of a plant.
uint32_t plantLabel(const gpu::ExpandedPlant& plant, uint32_t plantInTile) {
    const uint32_t state = (plant.fade >> 17) & 0xfu;
    const uint32_t semantic = state == gpu::kPlantStateFelled ? gpu::kSemanticFelled
                              : state == gpu::kPlantStateCut  ? gpu::kSemanticCut
                                                              : gpu::kSemanticVegetation + (plant.attributes & 3u);
    return (semantic << gpu::kInstanceBits) | (plantInTile + 1u);
}

bool rayHitsBox(glm::vec3 o, glm::vec3 inv, glm::vec3 lo, glm::vec3 hi, float tNear, float tFar) {
    const glm::vec3 a = (lo - o) * inv, b = (hi - o) * inv;
    const glm::vec3 mn = glm::min(a, b), mx = glm::max(a, b);
    return std::max({mn.x, mn.y, mn.z, tNear}) <= std::min({mx.x, mx.y, mx.z, tFar});
}

// The nearest hit of o + t d (t in [tNear, best)) on a plant's blade triangles (Moller-Trumbore, two-sided; blades
// are opaque).
bool intersectBlades(const PlantQuads& p, glm::vec3 o, glm::vec3 d, float tNear, float& best, glm::vec3& normal) {
    bool hit = false;
    for (size_t k = 0; k + 2 < p.blades.size(); k += 3) {
        const glm::vec3 p0 = p.blades[k], e1 = p.blades[k + 1] - p0, e2 = p.blades[k + 2] - p0;
        const glm::vec3 q = glm::cross(d, e2);
        const float det = glm::dot(e1, q);
        if (std::abs(det) < 1e-20f) continue;
        const float inv = 1.0f / det;
        const glm::vec3 s = o - p0;
        const float b1 = glm::dot(s, q) * inv;
        const glm::vec3 r = glm::cross(s, e1);
        const float b2 = glm::dot(d, r) * inv, t = glm::dot(e2, r) * inv;
        if (b1 < 0.0f || b2 < 0.0f || b1 + b2 > 1.0f || t < tNear || t >= best) continue;
        best = t, normal = glm::cross(e1, e2), hit = true;
    }
    return hit;
}

} // namespace

AtlasAlpha::AtlasAlpha(const Atlas& atlas) {
    if (atlas.mips.empty()) return; // no vegetation: never sampled
    const AtlasMip& mip = atlas.mips[0];
    width = mip.width, height = mip.height;
    alpha.resize(size_t(mip.width) * mip.height);
    for (size_t i = 0; i < alpha.size(); ++i) alpha[i] = mip.rgba[4 * i + 3];
    // Texel alpha k / 255 is >= 0.5 exactly when k >= 128, and then by at least 0.002: far above rounding.
    const size_t stride = size_t(width) + 1;
    between_.assign((stride * (size_t(height) + 1) + 3) / 4, 0);
    for (int64_t j = -1; j < int64_t(height); ++j)
        for (int64_t i = -1; i < int64_t(width); ++i) {
            int opaqueTexels = 0;
            for (int64_t dj = 0; dj < 2; ++dj)
                for (int64_t di = 0; di < 2; ++di) {
                    const int64_t x = std::clamp<int64_t>(i + di, 0, width - 1),
                                  y = std::clamp<int64_t>(j + dj, 0, height - 1);
                    opaqueTexels += alpha[size_t(y) * width + size_t(x)] >= 128;
                }
            const uint8_t c = opaqueTexels == 0 ? 0 : opaqueTexels == 4 ? 2 : 1;
            const size_t k = size_t(j + 1) * stride + size_t(i + 1);
            between_[k / 4] |= uint8_t(c << (2 * (k % 4)));
        }
    const AtlasDesc& desc = atlas.desc;
    maxColumns = desc.maxColumns();
    uvRects.resize(desc.rows.size() * maxColumns, glm::vec4(0.0f));
    baseAspects.resize(uvRects.size(), glm::vec3(0.5f, 1.0f, 1.0f));
    for (uint32_t r = 0; r < desc.rows.size(); ++r) {
        if (r < 4) columns[r] = uint32_t(desc.rows[r].cells.size());
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c) {
            const auto uv = desc.cellUvRect(r, c);
            const AtlasCell& cell = desc.rows[r].cells[c];
            uvRects[r * maxColumns + c] = glm::vec4(uv[0], uv[1], uv[2], uv[3]);
            baseAspects[r * maxColumns + c] = glm::vec3(cell.baseU, cell.baseV, cell.aspect);
        }
    }
}

float AtlasAlpha::sample(glm::vec2 uv) const {
    const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    auto at = [&](float i, float j) {
        const int64_t ii = std::clamp<int64_t>(int64_t(i), 0, int64_t(width) - 1);
        const int64_t jj = std::clamp<int64_t>(int64_t(j), 0, int64_t(height) - 1);
        return float(alpha[size_t(jj) * width + size_t(ii)]) * (1.0f / 255.0f);
    };
    const float top = at(x0, y0) * (1.0f - fx) + at(x0 + 1.0f, y0) * fx;
    const float bottom = at(x0, y0 + 1.0f) * (1.0f - fx) + at(x0 + 1.0f, y0 + 1.0f) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

bool AtlasAlpha::opaque(glm::vec2 uv) const {
    const float x = std::floor(uv.x * float(width) - 0.5f), y = std::floor(uv.y * float(height) - 0.5f);
    const int64_t i = std::clamp<int64_t>(int64_t(x) + 1, 0, width), j = std::clamp<int64_t>(int64_t(y) + 1, 0, height);
    const size_t k = size_t(j) * (size_t(width) + 1) + size_t(i);
    const uint32_t c = (between_[k / 4] >> (2 * (k % 4))) & 3u;
    return c == 1 ? sample(uv) >= 0.5f : c == 2;
}

uint32_t AtlasAlpha::cellOf(uint32_t attributes) const {
    const uint32_t category = attributes & 3u, variant = (attributes >> 2) & 63u;
    return category * maxColumns + variant % std::max(columns[category], 1u);
}

UnbentPlant unbentPlant(const AtlasAlpha& atlas, const VegetationParams& vegetation, const FieldVegetation& field,
                        uint32_t i) {
    const WindParams still{.strength = 0.0f, .gustStrength = 0.0f, .flutter = 0.0f};
    const gpu::ExpandedPlant plant = expandWholePlant(vegetation, still, field, i, restingPlantDynamic(), 0.0);
    UnbentPlant u;
    unbentQuadCorners(plant, gpu::kLodNear, atlas.baseAspects[atlas.cellOf(plant.attributes)], u.corners, u.bends);
    return u;
}

PlantQuads plantQuads(const AtlasAlpha& atlas, const VegetationParams& vegetation, const WindParams& wind,
                      const FieldVegetation& field, uint32_t i, uint32_t plantInTile, const gpu::PlantDynamic& dynamic,
                      double time, const UnbentPlant* unbent, uint32_t blades) {
    PlantQuads p;
    const gpu::ExpandedPlant plant = expandWholePlant(vegetation, wind, field, i, dynamic, time);
    p.cell = atlas.cellOf(plant.attributes);
    p.cutFraction = float(plant.fade >> 24) * (1.0f / 255.0f);
    p.mirrored = plantRandom(plant) > 0.5f;
    p.label = plantLabel(plant, plantInTile);
    p.present = plant.positionHeight.w > 0.0f;
    if (blades > 0) {
        p.blades = referenceBladeVertices(plant, blades, atlas.baseAspects[p.cell].z);
        p.lo = p.hi = p.blades[0];
        for (const glm::vec3& c : p.blades) p.lo = glm::min(p.lo, c), p.hi = glm::max(p.hi, c);
        return p;
    }
    glm::vec3 corners[4 * gpu::kQuadsNear];
    if (unbent) {
        const glm::vec2 tip = glm::unpackHalf2x16(plant.tip);
        const glm::vec3 up = decodeOctahedral(plant.up);
        for (uint32_t k = 0; k < 4 * gpu::kQuadsNear; ++k)
            corners[k] = bentPoint(unbent->corners[k], unbent->bends[k], tip, plant.positionHeight.w, up);
    } else {
        plantQuadCorners(plant, gpu::kLodNear, glm::vec3(0.0f), atlas.baseAspects[p.cell], corners);
    }
    p.lo = p.hi = corners[0];
    for (const glm::vec3& c : corners) p.lo = glm::min(p.lo, c), p.hi = glm::max(p.hi, c);
    static const uint32_t kTriangle[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (uint32_t t = 0; t < PlantQuads::kTriangles; ++t) {
        const glm::vec3* c = &corners[4 * (t / 2)];
        const glm::vec3 p0 = c[kTriangle[t % 2][0]], e1 = c[kTriangle[t % 2][1]] - p0, e2 = c[kTriangle[t % 2][2]] - p0;
        for (int k = 0; k < 3; ++k) p.p0[k][t] = p0[k], p.e1[k][t] = e1[k], p.e2[k][t] = e2[k];
    }
    return p;
}

uint32_t bladesOf(const VegetationParams& vegetation, uint32_t nearBlades, uint32_t category) {
    return nearBlades > 0 && category < vegetation.categoryCount &&
                   atlasPlantKindForCategory(vegetation.categories[category].name) == AtlasPlantKind::Grass
               ? nearBlades
               : 0u;
}

bool restingGeometry(const gpu::PlantDynamic& dynamic) {
    return dynamic.bend == 0u && ((dynamic.state >> 20) & 0xfu) == gpu::kPlantStateRest &&
           (dynamic.state >> 24) == gpu::kPlantUncut;
}

WindTipRange windTipRange(const WindParams& wind) {
    // windTip: direction * (strength * (0.8 + 0.2 sway) + gust * wave^2) + across * flutter * sin, with |sway| <= 1 and
    // 0 <= wave <= 1; the clamp to kMaxTipOffset only shortens it.
    const glm::vec2 dir = wind.direction(), across(-dir.y, dir.x);
    const float s = wind.strength, g = wind.gustStrength, f = std::abs(wind.flutter);
    const float alongLo = std::min({0.6f * s, s, 0.6f * s + g, s + g}),
                alongHi = std::max({0.6f * s, s, 0.6f * s + g, s + g});
    WindTipRange r{glm::vec2(std::numeric_limits<float>::max()), glm::vec2(-std::numeric_limits<float>::max()), 0.0f};
    for (float a : {alongLo, alongHi})
        for (float b : {-f, f}) {
            const glm::vec2 tip = dir * a + across * b;
            r.lo = glm::min(r.lo, tip), r.hi = glm::max(r.hi, tip);
            r.length = std::max(r.length, glm::length(tip));
        }
    r.length = std::min(r.length, float(gpu::kMaxTipOffset));
    return r;
}

void restingBounds(const AtlasAlpha& atlas, const VegetationParams& vegetation, const FieldVegetation& field,
                   uint32_t i, const UnbentPlant& unbent, const WindTipRange& wind, glm::vec3& lo, glm::vec3& hi,
                   uint32_t blades) {
    glm::vec3 stillLo = unbent.corners[0], stillHi = unbent.corners[0];
    for (const glm::vec3& c : unbent.corners) stillLo = glm::min(stillLo, c), stillHi = glm::max(stillHi, c);
    const glm::vec3 cell = atlas.baseAspects[atlas.cellOf(field.staticRecords[i].attributes)];
    if (blades > 0) { // the blades without wind; they bend by the same law as the quads, by at most fraction^2 <= 1
        const WindParams still{.strength = 0.0f, .gustStrength = 0.0f, .flutter = 0.0f};
        const gpu::ExpandedPlant plant = expandWholePlant(vegetation, still, field, i, restingPlantDynamic(), 0.0);
        const std::vector<glm::vec3> points = referenceBladeVertices(plant, blades, cell.z);
        stillLo = stillHi = points[0];
        for (const glm::vec3& c : points) stillLo = glm::min(stillLo, c), stillHi = glm::max(stillHi, c);
    }
    const float h = vegetation.categories[field.staticRecords[i].attributes & 3u].height *
                    (float(decodePlantStatic(field.staticRecords[i]).size) / gpu::kPlantSizeDivisor);
    // quadPoint: a corner moves by tip * h * fraction^2 sideways and drops by h (1 - sqrt(1 - |tip|^2)) * fraction^2
    // along the plant's up; fraction^2 is at most 1, or ((1 - baseV) / baseV)^2 below the base of a cell whose base is
    // above its bottom edge. The tip lies in `wind`'s box (or is clamped shorter, towards zero).
    const float below = cell.y > 0.0f ? (1.0f - cell.y) / cell.y : 0.0f;
    const float reach = h * std::max(1.0f, below * below);
    const float drop = reach * (1.0f - std::sqrt(std::max(1.0f - wind.length * wind.length, 0.0f)));
    const float margin = 1e-4f + 1e-5f * h;
    const glm::vec2 sideLo = glm::min(glm::vec2(0.0f), wind.lo * reach),
                    sideHi = glm::max(glm::vec2(0.0f), wind.hi * reach);
    lo = stillLo + glm::vec3(sideLo - drop - margin, -drop - margin);
    hi = stillHi + glm::vec3(sideHi + drop + margin, margin);
}

bool intersectPlant(const PlantQuads& p, const AtlasAlpha& atlas, glm::vec3 o, glm::vec3 d, float tNear, float& best,
                    glm::vec3& normal) {
    if (!p.present || !rayHitsBox(o, 1.0f / d, p.lo, p.hi, tNear, best)) return false;
    if (!p.blades.empty()) return intersectBlades(p, o, d, tNear, best, normal);
    // Moller-Trumbore (two-sided) on all eight triangles at once: distance t and barycentrics b1, b2 of p1, p2.
    constexpr uint32_t n = PlantQuads::kTriangles;
    float t[n], b1[n], b2[n], det[n];
    for (uint32_t i = 0; i < n; ++i) { // branch-free, so the compiler runs it on SIMD lanes
        const float e1x = p.e1[0][i], e1y = p.e1[1][i], e1z = p.e1[2][i], e2x = p.e2[0][i], e2y = p.e2[1][i],
                    e2z = p.e2[2][i];
        const float px = d.y * e2z - d.z * e2y, py = d.z * e2x - d.x * e2z, pz = d.x * e2y - d.y * e2x;
        det[i] = e1x * px + e1y * py + e1z * pz;
        const float sx = o.x - p.p0[0][i], sy = o.y - p.p0[1][i], sz = o.z - p.p0[2][i];
        const float qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
        b1[i] = sx * px + sy * py + sz * pz;
        b2[i] = d.x * qx + d.y * qy + d.z * qz;
        t[i] = e2x * qx + e2y * qy + e2z * qz;
    }
    bool inside[n];
    for (uint32_t i = 0; i < n; ++i) {
        const float inv = 1.0f / det[i];
        b1[i] *= inv, b2[i] *= inv, t[i] *= inv;
        inside[i] = std::abs(det[i]) >= 1e-20f && b1[i] >= 0.0f && b2[i] >= 0.0f && b1[i] + b2[i] <= 1.0f &&
                    t[i] >= tNear && t[i] < best;
    }
    // The nearest triangle whose texel there is opaque: uv interpolated over the triangle as plant_vertex.glsl sets it.
    static const glm::vec2 kCorner[2][3] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
    const glm::vec4 rect = atlas.uvRects[p.cell];
    bool hit = false;
    for (;;) {
        uint32_t nearest = n;
        for (uint32_t i = 0; i < n; ++i)
            if (inside[i] && (nearest == n || t[i] < t[nearest])) nearest = i;
        if (nearest == n) return hit;
        inside[nearest] = false;
        const glm::vec2* c = kCorner[nearest % 2];
        const glm::vec2 corner = c[0] * (1.0f - b1[nearest] - b2[nearest]) + c[1] * b1[nearest] + c[2] * b2[nearest];
        const glm::vec2 cellUv(p.mirrored ? 1.0f - corner.x : corner.x, 1.0f - corner.y * p.cutFraction);
        if (!atlas.opaque(glm::mix(glm::vec2(rect.x, rect.y), glm::vec2(rect.z, rect.w), cellUv))) continue;
        best = t[nearest];
        normal = glm::cross(glm::vec3(p.e1[0][nearest], p.e1[1][nearest], p.e1[2][nearest]),
                            glm::vec3(p.e2[0][nearest], p.e2[1][nearest], p.e2[2][nearest]));
        return true;
    }
}

} // namespace sward
