#include "interaction/ground_tracks.h"

#include "common/error.h"
#include "common/hash.h"
#include "shared/gpu_layout.h"
#include "world/ground.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

constexpr int64_t kBlock = gpu::kTrackBlockCells;

int64_t floorDiv(int64_t a, int64_t b) {
    return a / b - ((a % b != 0) && ((a < 0) != (b < 0)));
}

// The lattice index range [first, last] of vertices within `reach` metres of [lo, hi].
std::pair<int64_t, int64_t> latticeRange(float lo, float hi, float reach) {
    return {int64_t(std::floor(double(lo - reach) / gpu::kTrackCell)),
            int64_t(std::ceil(double(hi + reach) / gpu::kTrackCell))};
}

// The direction lugs repeat along: across a capsule's axle (a wheel rolls that way), else the way the hull moves
// (x when it stands). The sign is fixed, so the grooves of two ticks fall on the same lattice lines.
glm::vec2 treadDirection(const Collider& c, glm::vec2 motion) {
    glm::vec2 d = motion;
    if (c.shape == ColliderShape::Capsule) d = glm::vec2(c.centre.y - c.end.y, c.end.x - c.centre.x);
    if (glm::dot(d, d) < 1e-12f) d = glm::vec2(1.0f, 0.0f);
    d = glm::normalize(d);
    return d.x < 0.0f || (d.x == 0.0f && d.y < 0.0f) ? -d : d;
}

constexpr uint64_t kTreadDomain = 0x5452454144303031ull; // "TREAD001"

// How far a groove between two lugs raises the rut's floor, as a share of the tread depth, at u tread pitches along
// the direction of travel. Lug k spans [k, k + 1): its groove starts at a point jittered by up to 15 % of the pitch
// around the middle, and is worn to 40-100 % of the full depth (soil falls back into it, a lug prints unevenly), so
// a print is no perfectly periodic pattern. The hash of k keeps it the same at every tick and in every run.
float treadGroove(float u) {
    const double lug = std::floor(double(u));
    const uint64_t h = hashKey({kTreadDomain, uint64_t(int64_t(lug))});
    const double start = 0.5 + 0.3 * (unitDouble(mix64(h ^ 1u)) - 0.5), wear = 0.4 + 0.6 * unitDouble(mix64(h ^ 2u));
    return double(u) - lug >= start ? float(wear) : 0.0f;
}

Collider moved(const Collider& c, glm::vec3 delta) {
    Collider out = c;
    out.centre += delta;
    out.end += delta;
    return out;
}

} // namespace

glm::vec2 trackVertexPosition(int64_t i, int64_t j) {
    return glm::vec2(float(double(i) * gpu::kTrackCell), float(double(j) * gpu::kTrackCell));
}

int32_t trackBlockOf(int64_t i) {
    return int32_t(floorDiv(i, kBlock));
}

float GroundTracks::depth(int64_t i, int64_t j) const {
    const auto it = blocks_.find({trackBlockOf(i), trackBlockOf(j)});
    if (it == blocks_.end()) return 0.0f;
    const int64_t li = i - int64_t(it->first.x) * kBlock, lj = j - int64_t(it->first.y) * kBlock;
    return it->second[size_t(lj * kBlock + li)];
}

void GroundTracks::pressVertex(int64_t i, int64_t j, float d) {
    if (!(d > 0.0f)) return;
    const int32_t bx = trackBlockOf(i), by = trackBlockOf(j);
    const size_t index = size_t((j - int64_t(by) * kBlock) * kBlock + (i - int64_t(bx) * kBlock));
    // The common case while a wheel rolls on: its earlier steps pressed this vertex as deep already.
    if (const auto owner = blocks_.find({bx, by}); owner != blocks_.end() && d <= owner->second[index]) return;
    // The block owning the vertex, and a block whose shared edge it lies on (its first row or column belongs to the
    // next block), so that where a patch meets the coarse ground every vertex is unpressed.
    for (int32_t y = by - (j % kBlock == 0 ? 1 : 0); y <= by; ++y)
        for (int32_t x = bx - (i % kBlock == 0 ? 1 : 0); x <= bx; ++x)
            blocks_.try_emplace({x, y}, size_t(kBlock * kBlock), 0.0f); // built only when new
    blocks_[{bx, by}][index] = d;
    // Every patch drawing this vertex or shading with it (its ring's normals look one vertex further): blocks b
    // with b * kBlock - ring - 1 <= i <= b * kBlock + kBlock + ring + 1.
    constexpr int64_t kReach = gpu::kTrackPatchRing + 1;
    for (int32_t y = trackBlockOf(j - kReach - 1); y <= trackBlockOf(j + kReach); ++y)
        for (int32_t x = trackBlockOf(i - kReach - 1); x <= trackBlockOf(i + kReach); ++x)
            if (blocks_.count({x, y})) revisions_[{x, y}] = revision_ + 1;
    changed_ = true;
}

void GroundTracks::pressHull(const Collider& hull, glm::vec2 forward, const Ground& ground) {
    const RutParams& rut = hull.rut;
    const Aabb bounds = worldBounds(hull);
    const auto [i0, i1] = latticeRange(bounds.min.x, bounds.max.x, rut.depth);
    const auto [j0, j1] = latticeRange(bounds.min.y, bounds.max.y, rut.depth);
    for (int64_t j = j0; j <= j1; ++j)
        for (int64_t i = i0; i <= i1; ++i) {
            const glm::vec2 xy = trackVertexPosition(i, j);
            const float gap = signedDistance(hull, glm::vec3(xy, ground.height(xy)));
            float d = std::min(rut.depth, rut.depth - gap);
            if (rut.treadPitch > 0.0f) d -= treadGroove(glm::dot(xy, forward) / rut.treadPitch) * rut.treadDepth;
            pressVertex(i, j, d);
        }
}

void GroundTracks::press(std::span<const Collider> previous, std::span<const Collider> current, const Ground& ground) {
    for (const Collider& c : current) {
        if (c.kind != ColliderKind::Push || !(c.rut.depth > 0.0f)) continue;
        const auto before =
            std::find_if(previous.begin(), previous.end(), [&](const Collider& p) { return p.id == c.id; });
        glm::vec3 motion(0.0f);
        if (before != previous.end() && glm::distance(before->centre, c.centre) <= kMaxSweep)
            motion = c.centre - before->centre;
        const glm::vec2 forward = treadDirection(c, glm::vec2(motion));
        // The previous pose was pressed at its own tick: steps 1..n reach this one.
        const int steps = std::max(1, int(std::ceil(glm::length(motion) / (0.5f * gpu::kTrackCell))));
        for (int s = 1; s <= steps; ++s)
            pressHull(moved(c, motion * (float(s - steps) / float(steps))), forward, ground);
    }
    // pressVertex stamped every block it changed with revision_ + 1.
    if (changed_) ++revision_;
    changed_ = false;
}

uint64_t GroundTracks::blockRevision(TrackBlockKey key) const {
    const auto it = revisions_.find(key);
    return it == revisions_.end() ? 0 : it->second;
}

void GroundTracks::restore(TrackBlocks blocks) {
    for (const auto& [key, block] : blocks) {
        require(block.size() == size_t(kBlock * kBlock),
                "a track block must hold " + std::to_string(kBlock * kBlock) + " depths");
        for (float d : block) require(std::isfinite(d) && d >= 0.0f, "a rut depth must be finite and >= 0");
    }
    blocks_ = std::move(blocks);
    ++revision_;
    revisions_.clear();
    for (const auto& entry : blocks_) revisions_[entry.first] = revision_;
    ++generation_;
}

} // namespace sward
