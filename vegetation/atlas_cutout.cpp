#include "vegetation/atlas_cutout.h"

#include "common/error.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

using glm::vec2;

float cross2(vec2 a, vec2 b) {
    return a.x * b.y - a.y * b.x;
}

// Convex hull (Andrew's monotone chain), counter-clockwise in (u, v) with v down, collinear points dropped.
std::vector<vec2> convexHull(std::vector<vec2> points) {
    std::sort(points.begin(), points.end(), [](vec2 a, vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 3) return points;
    std::vector<vec2> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0f) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0f) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

// The corners of every footprint that may pass the alpha test: per level and texel row, the outermost texels with
// alpha > 0 grown by the margin, clamped to the cell (the quad ends there). Interior texels add nothing to a hull.
std::vector<vec2> footprintCorners(const Atlas& atlas, uint32_t row, uint32_t column, uint32_t maxLevel) {
    std::vector<vec2> points;
    for (uint32_t level = 0; level <= maxLevel; ++level) {
        const AtlasMip& mip = atlas.mips[level];
        const AtlasRect rect = atlas.desc.cellRect(row, column, level);
        const float texelU = 1.0f / float(rect.width), texelV = 1.0f / float(rect.height);
        const float growU = gpu::kCutoutMarginTexels * texelU, growV = gpu::kCutoutMarginTexels * texelV;
        for (uint32_t y = 0; y < rect.height; ++y) {
            int first = -1, last = -1;
            for (uint32_t x = 0; x < rect.width; ++x)
                if (mip.rgba[(size_t(rect.y + y) * mip.width + rect.x + x) * 4 + 3] > 0) {
                    if (first < 0) first = int(x);
                    last = int(x);
                }
            if (first < 0) continue;
            const float u0 = std::max(0.0f, float(first) * texelU - growU);
            const float u1 = std::min(1.0f, float(last + 1) * texelU + growU);
            const float v0 = std::max(0.0f, float(y) * texelV - growV);
            const float v1 = std::min(1.0f, float(y + 1) * texelV + growV);
            points.insert(points.end(), {vec2(u0, v0), vec2(u1, v0), vec2(u0, v1), vec2(u1, v1)});
        }
    }
    return points;
}

// Where the lines through edges (a0, a1) and (b0, b1) meet; false when they are parallel.
bool lineIntersection(vec2 a0, vec2 a1, vec2 b0, vec2 b1, vec2& out) {
    const vec2 da = a1 - a0, db = b1 - b0;
    const float denominator = cross2(da, db);
    if (std::abs(denominator) < 1e-12f) return false;
    out = a0 + da * (cross2(b0 - a0, db) / denominator);
    return true;
}

// Removes hull edges until at most `corners` corners remain: each step drops the edge whose two neighbours,
// extended to meet, add the least area (the result still contains the hull), as long as they meet inside the cell.
// Returns false if no edge can be dropped (the caller falls back to the whole cell).
bool reduceCorners(std::vector<vec2>& polygon, uint32_t corners) {
    while (polygon.size() > corners) {
        const size_t n = polygon.size();
        float bestArea = INFINITY;
        size_t best = n;
        vec2 bestPoint(0.0f);
        for (size_t i = 0; i < n; ++i) {
            // Edge (i, i + 1) goes; edges (i - 1, i) and (i + 1, i + 2) are extended to meet at p.
            const vec2 prev = polygon[(i + n - 1) % n], a = polygon[i], b = polygon[(i + 1) % n],
                       next = polygon[(i + 2) % n];
            vec2 p;
            if (!lineIntersection(prev, a, b, next, p)) continue;
            // p must lie beyond the edge (outside: right of it), on the forward rays of both neighbours.
            if (cross2(b - a, p - a) > 0.0f || glm::dot(p - a, a - prev) < 0.0f || glm::dot(p - b, b - next) < 0.0f)
                continue;
            if (p.x < 0.0f || p.x > 1.0f || p.y < 0.0f || p.y > 1.0f) continue;
            const float area = 0.5f * std::abs(cross2(b - a, p - a));
            if (area < bestArea) bestArea = area, best = i, bestPoint = p;
        }
        if (best == n) return false;
        polygon[best] = bestPoint;
        polygon.erase(polygon.begin() + long((best + 1) % n));
    }
    return true;
}

CutoutPolygon padded(const std::vector<vec2>& corners) {
    CutoutPolygon polygon;
    polygon.count = uint32_t(corners.size());
    for (uint32_t i = 0; i < gpu::kMaxCutoutCorners; ++i)
        polygon.corners[i] = corners[std::min<size_t>(i, corners.size() - 1)];
    return polygon;
}

CutoutPolygon cellCutout(const Atlas& atlas, uint32_t row, uint32_t column, uint32_t corners, uint32_t maxLevel) {
    std::vector<vec2> hull = convexHull(footprintCorners(atlas, row, column, maxLevel));
    if (hull.size() < 3 || !reduceCorners(hull, corners)) return fullCellPolygon();
    return padded(hull);
}

} // namespace

bool CutoutPolygon::contains(glm::vec2 p) const {
    for (uint32_t i = 0; i < count; ++i) {
        const vec2 a = corners[i], b = corners[(i + 1) % count];
        // Counter-clockwise in (u, v): inside is to the left; a little slack for the rounding of the corners.
        if (cross2(b - a, p - a) < -1e-6f) return false;
    }
    return true;
}

float CutoutPolygon::area() const {
    float twice = 0.0f;
    for (uint32_t i = 0; i < count; ++i) twice += cross2(corners[i], corners[(i + 1) % count]);
    return 0.5f * std::abs(twice);
}

CutoutPolygon fullCellPolygon() {
    return padded({vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f)});
}

std::vector<CutoutPolygon> atlasCutouts(const Atlas& atlas, uint32_t corners, uint32_t maxLevel) {
    require(!atlas.mips.empty(), "atlasCutouts: the atlas has no image");
    require(corners >= 4 && corners <= gpu::kMaxCutoutCorners, "atlasCutouts: a cut-out has 4..8 corners");
    maxLevel = std::min<uint32_t>(maxLevel, uint32_t(atlas.mips.size()) - 1);
    const uint32_t columns = atlas.desc.maxColumns();
    std::vector<CutoutPolygon> polygons(atlas.desc.rows.size() * columns, fullCellPolygon());
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c)
            polygons[r * columns + c] = cellCutout(atlas, r, c, corners, maxLevel);
    return polygons;
}

} // namespace sward
