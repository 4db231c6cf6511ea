#include "world/ground.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sward {

namespace {

// cos(x) for x in [0, pi/2] by its Taylor series, + - * / only: libm's cos may differ in the last bit between
// machines, and this value decides which triangles carry plants (docs/architecture.md, "No libm transcendentals").
// 14 terms leave a remainder below (pi/2)^28 / 28! ~ 1e-24.
double taylorCos(double x) {
    double term = 1.0, sum = 1.0;
    for (int k = 1; k <= 14; ++k) {
        term *= -x * x / double((2 * k - 1) * (2 * k));
        sum += term;
    }
    return sum;
}

// The smallest normal z a plant may stand on: cos(maxSlope); 0 for no limit (every surface seen from above).
float minNormalZ(const GroundSelection& selection) {
    require(selection.maxSlopeDegrees > 0.0 && selection.maxSlopeDegrees <= 90.0,
            "the slope limit must lie in (0, 90] degrees");
    return selection.maxSlopeDegrees >= 90.0 ? 0.0f
                                             : float(taylorCos(selection.maxSlopeDegrees * (std::numbers::pi / 180.0)));
}

std::string materialList(const std::vector<GroundMaterial>& materials) {
    std::string list;
    for (const GroundMaterial& m : materials) list += (list.empty() ? "'" : ", '") + m.name + "'";
    return list.empty() ? "none" : list;
}

// Per triangle: is its material one of the selected ones. Every selected name must exist in the mesh.
std::vector<uint8_t> selectTriangles(const TriangleMesh& mesh, const std::vector<std::string>& names) {
    const size_t triangles = mesh.indices.size() / 3;
    if (names.empty()) return std::vector<uint8_t>(triangles, 1);
    std::vector<uint8_t> selectedMaterial(mesh.materials.size(), 0);
    for (const std::string& name : names) {
        bool found = false;
        for (size_t m = 0; m < mesh.materials.size(); ++m)
            if (mesh.materials[m].name == name) selectedMaterial[m] = 1, found = true;
        require(found, "material '" + name + "' is not in the ground mesh (its materials: " +
                           materialList(mesh.materials) + ")");
    }
    std::vector<uint8_t> plantable(triangles, 0);
    for (size_t t = 0; t < mesh.triangleMaterial.size(); ++t) plantable[t] = selectedMaterial[mesh.triangleMaterial[t]];
    return plantable;
}

} // namespace

Ground::Ground(Heightfield heightfield, GroundSelection selection) : heightfield_(std::move(heightfield)) {
    boundsMin_ = heightfield_->origin();
    boundsMax_ = heightfield_->origin() + heightfield_->extent();
    minHeight_ = heightfield_->minHeight();
    maxHeight_ = heightfield_->maxHeight();
    require(selection.materials.empty(), "a heightfield ground has no materials to select");
    minNormalZ_ = minNormalZ(selection);
}

Ground::Ground(TriangleMesh mesh, GroundSelection selection, float cellSize) : mesh_(std::move(mesh)) {
    const auto& p = mesh_.positions;
    const auto& idx = mesh_.indices;
    require(idx.size() % 3 == 0, "ground mesh index count is not a multiple of 3");
    // Plain checks rather than require(), whose message string would be built once per element.
    for (uint32_t i : idx)
        if (i >= p.size()) throw Error("ground mesh index " + std::to_string(i) + " is out of range");
    for (const glm::vec3& v : p)
        if (!std::isfinite(v.x + v.y + v.z)) throw Error("ground mesh has a non-finite vertex");
    const uint32_t triangles = uint32_t(idx.size() / 3);
    require(mesh_.normals.empty() || mesh_.normals.size() == p.size(), "ground mesh needs one normal per vertex");
    require(mesh_.uvs.empty() || mesh_.uvs.size() == p.size(), "ground mesh needs one uv per vertex");
    for (const GroundMaterial& m : mesh_.materials)
        require(m.texture < int(mesh_.textures.size()), "ground mesh material texture out of range");
    require(mesh_.triangleMaterial.empty() || mesh_.triangleMaterial.size() == triangles,
            "ground mesh needs one material per triangle");
    for (uint32_t m : mesh_.triangleMaterial)
        if (m >= mesh_.materials.size()) throw Error("ground mesh material " + std::to_string(m) + " is out of range");
    if (!selection.materials.empty() && mesh_.triangleMaterial.empty())
        throw Error("the ground mesh has no materials to select");
    plantable_ = selectTriangles(mesh_, selection.materials);
    minNormalZ_ = minNormalZ(selection);

    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    double edgeSum = 0.0;
    uint32_t usable = 0;
    for (uint32_t t = 0; t < triangles; ++t) {
        glm::vec3 a = p[idx[3 * t]], b = p[idx[3 * t + 1]], c = p[idx[3 * t + 2]];
        lo = glm::min(lo, glm::min(glm::vec2(a), glm::min(glm::vec2(b), glm::vec2(c))));
        hi = glm::max(hi, glm::max(glm::vec2(a), glm::max(glm::vec2(b), glm::vec2(c))));
        edgeSum += glm::length(glm::vec2(b - a)) + glm::length(glm::vec2(c - b)) + glm::length(glm::vec2(a - c));
        usable += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) != 0.0f;
    }
    require(usable > 0, "ground mesh has no triangle that is visible from above");
    boundsMin_ = lo;
    boundsMax_ = hi;
    minHeight_ = std::numeric_limits<float>::max();
    maxHeight_ = -std::numeric_limits<float>::max();
    for (uint32_t i : idx) minHeight_ = std::min(minHeight_, p[i].z), maxHeight_ = std::max(maxHeight_, p[i].z);
    for (uint32_t t = 0; t < triangles; ++t) {
        if (!plantable_[t]) continue;
        const glm::dvec3 a(p[idx[3 * t]]), b(p[idx[3 * t + 1]]), c(p[idx[3 * t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double length = std::sqrt(glm::dot(n, n));
        plantable_[t] = length > 0.0 && std::abs(n.z) / length >= double(minNormalZ_) && n.z != 0.0;
        plantableTriangles_ += plantable_[t];
    }

    // Two mean edge lengths per cell keeps a handful of triangles per cell; cap the cell count for huge extents.
    const glm::vec2 extent = glm::max(hi - lo, glm::vec2(1e-3f));
    cellSize_ = cellSize > 0.0f ? cellSize : float(std::max(2.0 * edgeSum / (3.0 * triangles), 1e-3));
    cellSize_ = std::max(cellSize_, std::sqrt(extent.x * extent.y / float(1u << 22)));
    gridWidth_ = uint32_t(extent.x / cellSize_) + 1;
    gridHeight_ = uint32_t(extent.y / cellSize_) + 1;

    auto cellRange = [&](uint32_t t) {
        glm::vec3 a = p[idx[3 * t]], b = p[idx[3 * t + 1]], c = p[idx[3 * t + 2]];
        glm::vec2 tlo = glm::min(glm::vec2(a), glm::min(glm::vec2(b), glm::vec2(c))) - lo;
        glm::vec2 thi = glm::max(glm::vec2(a), glm::max(glm::vec2(b), glm::vec2(c))) - lo;
        glm::uvec2 c0 = glm::min(glm::uvec2(tlo / cellSize_), glm::uvec2(gridWidth_ - 1, gridHeight_ - 1));
        glm::uvec2 c1 = glm::min(glm::uvec2(thi / cellSize_), glm::uvec2(gridWidth_ - 1, gridHeight_ - 1));
        return std::pair(c0, c1);
    };
    // Counting sort into CSR: count per cell, prefix sum, then fill in triangle order (deterministic).
    cellStart_.assign(size_t(gridWidth_) * gridHeight_ + 1, 0);
    for (uint32_t t = 0; t < triangles; ++t) {
        auto [c0, c1] = cellRange(t);
        for (uint32_t y = c0.y; y <= c1.y; ++y)
            for (uint32_t x = c0.x; x <= c1.x; ++x) ++cellStart_[size_t(y) * gridWidth_ + x + 1];
    }
    for (size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
    cellTriangles_.resize(cellStart_.back());
    std::vector<uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (uint32_t t = 0; t < triangles; ++t) {
        auto [c0, c1] = cellRange(t);
        for (uint32_t y = c0.y; y <= c1.y; ++y)
            for (uint32_t x = c0.x; x <= c1.x; ++x) cellTriangles_[fill[size_t(y) * gridWidth_ + x]++] = t;
    }
}

std::optional<SurfacePoint> Ground::surface(glm::vec2 xy) const {
    if (heightfield_) {
        if (xy.x < boundsMin_.x || xy.y < boundsMin_.y || xy.x > boundsMax_.x || xy.y > boundsMax_.y)
            return std::nullopt;
        const glm::vec3 normal = heightfield_->normal(xy);
        return SurfacePoint{heightfield_->height(xy), normal, normal.z >= minNormalZ_};
    }
    return meshSurface(xy);
}

float Ground::height(glm::vec2 xy) const {
    if (heightfield_) return heightfield_->height(xy);
    const std::optional<SurfacePoint> s = meshSurface(glm::clamp(xy, boundsMin_, boundsMax_));
    return s ? s->height : minHeight_;
}

std::optional<double> Ground::raycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const {
    return heightfield_ ? heightfield_->raycast(origin, direction, maxDistance)
                        : meshRaycast(origin, direction, maxDistance);
}

// Every triangle is tested (Moeller-Trumbore in double): O(triangles), for interactive picks, not per pixel.
std::optional<double> Ground::meshRaycast(glm::dvec3 origin, glm::dvec3 direction, double maxDistance) const {
    std::optional<double> best;
    for (size_t t = 0; t + 2 < mesh_.indices.size(); t += 3) {
        const glm::dvec3 a(mesh_.positions[mesh_.indices[t]]), b(mesh_.positions[mesh_.indices[t + 1]]),
            c(mesh_.positions[mesh_.indices[t + 2]]);
        const glm::dvec3 e1 = b - a, e2 = c - a, pv = glm::cross(direction, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0) continue;
        const glm::dvec3 tv = origin - a;
        const double u = glm::dot(tv, pv) / det;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(direction, qv) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double distance = glm::dot(e2, qv) / det;
        if (distance >= 0.0 && distance <= maxDistance && (!best || distance < *best)) best = distance;
    }
    return best;
}

std::optional<SurfacePoint> Ground::meshSurface(glm::vec2 xy) const {
    if (cellStart_.empty() || xy.x < boundsMin_.x || xy.y < boundsMin_.y || xy.x > boundsMax_.x || xy.y > boundsMax_.y)
        return std::nullopt;
    const glm::vec2 local = (xy - boundsMin_) / cellSize_;
    const uint32_t cx = std::min(uint32_t(local.x), gridWidth_ - 1), cy = std::min(uint32_t(local.y), gridHeight_ - 1);
    const size_t cell = size_t(cy) * gridWidth_ + cx;
    std::optional<SurfacePoint> best;
    const double px = xy.x, py = xy.y;
    for (uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
        const uint32_t t = cellTriangles_[k];
        const glm::dvec3 a(mesh_.positions[mesh_.indices[3 * t]]), b(mesh_.positions[mesh_.indices[3 * t + 1]]),
            c(mesh_.positions[mesh_.indices[3 * t + 2]]);
        // 2D barycentrics of the vertical line through xy. A tiny negative tolerance closes the cracks that
        // rounding would open along shared edges; a hit is then found by both neighbours, with equal heights.
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0.0) continue; // vertical triangle: invisible from above
        const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
        const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
        const double w2 = 1.0 - w0 - w1;
        constexpr double kEps = -1e-9;
        if (w0 < kEps || w1 < kEps || w2 < kEps) continue;
        const float z = float(w0 * a.z + w1 * b.z + w2 * c.z);
        if (best && z <= best->height) continue;
        glm::dvec3 n = glm::cross(b - a, c - a);
        if (n.z < 0.0) n = -n; // winding-independent: ground faces up
        best = SurfacePoint{z, glm::vec3(n / std::sqrt(glm::dot(n, n))), plantable_[t] != 0, t};
    }
    return best;
}

} // namespace sward
