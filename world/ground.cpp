#include "world/ground.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sward {

Ground::Ground(Heightfield heightfield) : heightfield_(std::move(heightfield)) {
    boundsMin_ = heightfield_->origin();
    boundsMax_ = heightfield_->origin() + heightfield_->extent();
}

Ground::Ground(TriangleMesh mesh, float cellSize) : mesh_(std::move(mesh)) {
    const auto& p = mesh_.positions;
    const auto& idx = mesh_.indices;
    require(idx.size() % 3 == 0, "ground mesh index count is not a multiple of 3");
    // Plain checks rather than require(), whose message string would be built once per element.
    for (uint32_t i : idx)
        if (i >= p.size()) throw Error("ground mesh index " + std::to_string(i) + " is out of range");
    for (const glm::vec3& v : p)
        if (!std::isfinite(v.x + v.y + v.z)) throw Error("ground mesh has a non-finite vertex");
    const uint32_t triangles = uint32_t(idx.size() / 3);

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
        return SurfacePoint{heightfield_->height(xy), heightfield_->normal(xy)};
    }
    return meshSurface(xy);
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
        best = SurfacePoint{z, glm::vec3(n / std::sqrt(glm::dot(n, n)))};
    }
    return best;
}

} // namespace sward
