#include "interaction/collision.h"

#include "common/parallel_for.h"
#include "common/snorm.h"
#include "common/stopwatch.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <optional>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace sward {

// --- Per plant ---------------------------------------------------------------------------------------------------

namespace {

// A stem exactly on the axis has no "away": any fixed direction keeps the result deterministic.
inline glm::vec2 awayDirection(glm::vec2 away) {
    float len2 = glm::dot(away, away);
    return len2 > 1e-12f ? away / std::sqrt(len2) : glm::vec2(1.0f, 0.0f);
}

// How far a penetration `depth` at stem point q bends the plant (the rules in collision.h).
inline float bendOf(const Collider& c, glm::vec3 q, float depth, float height, const CategoryInteraction& response) {
    switch (c.kind) {
    case ColliderKind::Push:
    case ColliderKind::Gust:
    case ColliderKind::Mower:
        return response.pushGain * c.force * depth / height;
    case ColliderKind::Downwash: {
        float reach = c.centre.z - c.end.z;
        float below = reach > 0.0f ? std::clamp((c.centre.z - q.z) / reach, 0.0f, 1.0f) : 0.0f;
        return response.pushGain * c.force * depth / c.radius * (1.0f - 0.5f * below);
    }
    }
    return 0.0f;
}

// Whether collider c fells a plant of that response that it bends by `bend`. Only solid bodies carry weight: air
// (gusts, downwash) bends, and a mower's weight is on its wheels. A solid body fells by its weight or by bending the
// plant beyond what it takes.
inline bool fells(const Collider& c, float bend, const CategoryInteraction& response) {
    return c.kind == ColliderKind::Push && (c.force > response.fellForce || bend > response.maxBend);
}

// A mower's cut of a plant it pushes (t.kind kContactPush): below the plant's top it cuts.
inline void mowerCut(const Collider& c, float height, PlantTouch& t) {
    if (c.kind == ColliderKind::Mower && c.cutHeight < height) {
        t.kind = gpu::kContactCut;
        t.cut = uint32_t(std::clamp(std::floor(255.0f * c.cutHeight / height + 0.5f), 0.0f, 254.0f));
    }
}

// The touch of a plant bent by `bend` along dir (the rules in collision.h). Shared by touchPlant and the pass's
// general path; the sphere lanes compute the same with fells' and mowerCut's rules, so all give identical bits.
inline PlantTouch touchResponse(const Collider& c, float bend, glm::vec2 dir, float height,
                                const CategoryInteraction& response, const RecoveryParams& recovery) {
    PlantTouch t;
    if (fells(c, bend, response)) {
        t.kind = gpu::kContactFell;
        t.push = dir * recovery.fellBend;
        return t;
    }
    t.push = dir * std::min(bend, kMaxPush);
    t.kind = gpu::kContactPush;
    mowerCut(c, height, t);
    return t;
}

} // namespace

PlantTouch touchPlant(const Collider& c, glm::vec3 base, float height, const CategoryInteraction& response,
                      const RecoveryParams& recovery) {
    // The stem point nearest the collider's axis: exact for spheres and horizontal or vertical capsules (wheels,
    // downwash), a close approximation for tilted capsules and boxes.
    glm::vec3 axis = axisPoint(c, base + glm::vec3(0.0f, 0.0f, 0.5f * height));
    glm::vec3 q(base.x, base.y, std::clamp(axis.z, base.z, base.z + height));
    float sd = signedDistance(c, q);
    if (!(sd < 0.0f)) return {};
    axis = axisPoint(c, q);
    return touchResponse(c, bendOf(c, q, -sd, height, response), awayDirection({q.x - axis.x, q.y - axis.y}), height,
                         response, recovery);
}

namespace {

// Running combination of one plant's touches, fed in collider id order (combineTouches and the pass share it, so
// both give identical bits).
struct TouchSum {
    glm::vec2 sum{0.0f}, firstFell{0.0f};
    bool fell = false, cut = false;
    uint32_t cutByte = gpu::kPlantUncut;

    void add(const PlantTouch& t) {
        sum += t.push; // in collider id order: the float sum is reproducible
        if (t.kind == gpu::kContactFell && !fell) {
            fell = true;
            firstFell = t.push;
        }
        if (t.kind == gpu::kContactCut) {
            cut = true;
            cutByte = std::min(cutByte, t.cut);
        }
    }

    gpu::PlantContact contact(const RecoveryParams& recovery) const {
        glm::vec2 push;
        uint32_t flags;
        float len2 = glm::dot(sum, sum);
        if (fell) {
            push = len2 > 1e-12f ? sum * (recovery.fellBend / std::sqrt(len2)) : firstFell;
            flags = gpu::kContactFell;
        } else {
            push = len2 > kMaxPush * kMaxPush ? sum * (kMaxPush / std::sqrt(len2)) : sum;
            flags = cut ? gpu::kContactCut | (cutByte << 8) : gpu::kContactPush;
        }
        return {0u, packSnorm2x16(push.x, push.y), flags, 0u};
    }
};

} // namespace

gpu::PlantContact combineTouches(std::span<const PlantTouch> touches, const RecoveryParams& recovery) {
    assert(!touches.empty());
    TouchSum sum;
    for (const PlantTouch& t : touches) sum.add(t);
    return sum.contact(recovery);
}

// --- Pass --------------------------------------------------------------------------------------------------------

// Per worker, aligned apart (kWorkerScratchAlignment): touchedPlants is written at every touch, next to the vectors
// whose pointers every touch reads.
struct alignas(kWorkerScratchAlignment) CollisionPass::Scratch {
    std::array<std::vector<Run>, 2> runs; // of the field being tested and of the next one
    std::vector<TouchSum> sums;           // per plant of the field: its touches so far (reset once emitted)
    std::vector<uint64_t> touched; // per plant of the field, one bit: has a touch (read back in plant order)
    uint32_t touchedPlants = 0;
};

CollisionPass::CollisionPass(const VegetationTile& tile, const VegetationParams& vegetation,
                             const InteractionParams& params)
    : tile_(&tile), index_(tile, vegetation), params_(params), grid_(tile), outputs_(tile.fields.size()) {}

CollisionPass::~CollisionPass() = default;
CollisionPass::CollisionPass(CollisionPass&&) noexcept = default;
CollisionPass& CollisionPass::operator=(CollisionPass&&) noexcept = default;

namespace {

// Runs prefetched ahead of the one being tested: the plant index is far larger than the caches, and each run
// is a separate miss that the hardware prefetcher cannot foresee. Four runs are about 20 lines, as many misses as
// a core keeps in flight: measured on the 400 x 25 case, 48 runs cost 30 % more CPU time than 4 (prefetches
// beyond the core's miss buffers wait in its load queue and stall the tests), none 40 % more, 2-8 about the same.
constexpr uint32_t kPrefetchRuns = 4;

// Fields per task of the worker pool: enough to overlap one field's fetches with the previous field's tests, few
// enough to balance the load (400 fields make 50 tasks).
constexpr uint32_t kFieldsPerTask = 8;

// Asks for the cache lines of stems [begin, end) ahead of their use.
inline void prefetchStems(const TileCollisionIndex::Stem* stems, uint32_t begin, uint32_t end) {
    const char* p = reinterpret_cast<const char*>(stems + begin);
    const char* e = reinterpret_cast<const char*>(stems + end);
    for (p = reinterpret_cast<const char*>(uintptr_t(p) & ~uintptr_t(63)); p < e; p += 64) __builtin_prefetch(p);
}

} // namespace

// Step 1 for field f: its candidates and runs, into s.runs[buffer], with the first runs' stems on their way to the
// cache. Returns whether any collider meets the field.
bool CollisionPass::prepareField(uint32_t f, Scratch& s, uint32_t buffer, FieldOutput& out) const {
    const FieldVegetation& field = tile_->fields[f];
    if (field.plantCount() == 0) return false;
    bool any = false;
    for (uint32_t share = 0; share < grid_.shares(); ++share) any = any || !grid_.ranks(f, share).empty();
    if (!any) return false;
    out.tested = true;
    const TileCollisionIndex::Field& index = index_.field(f);
    out.clustersTested = index.clustersWithPlants;
    findCellRuns(f, index, s.runs[buffer]);
    return true;
}

// Steps 2 and 3 for a field that prepareField found runs for in s.runs[buffer].
void CollisionPass::finishField(uint32_t f, std::span<const Collider> colliders, Scratch& s, uint32_t buffer,
                                FieldOutput& out) const {
    const FieldVegetation& field = tile_->fields[f];
    out.plantsTested = touchStems(index_.field(f), field.plantCount(), colliders, s.runs[buffer], s);
    if (s.touchedPlants == 0) return;
    emitContacts(f, field, s, out);
}

// Step 1: the runs of stems under each candidate's footprint, candidates (the grid's shares one after the other) in
// rank (= id) order so each plant's touches are summed in id order. Only clusters under the collider's box are
// visited.
void CollisionPass::findCellRuns(uint32_t f, const TileCollisionIndex::Field& index, std::vector<Run>& runs) const {
    const FieldVegetation& field = tile_->fields[f];
    constexpr uint32_t kCellsX = TileCollisionIndex::kCellsX, kCellsY = TileCollisionIndex::kCellsY;
    const glm::vec2 invCell = 1.0f / index_.cellSize();
    const uint32_t perSide = tile_->clustersPerField;
    const float clusterSize = tile_->clusterSize, invCluster = 1.0f / clusterSize;
    // Cluster boxes may reach a little beyond their grid squares (position rounding, plant extents): the margin
    // keeps the range of clusters visited conservative, the exact cluster box test below decides.
    const float margin = index.overhang + 1e-3f;
    const glm::vec2 o = field.origin;
    runs.clear();
    for (uint32_t share = 0; share < grid_.shares(); ++share)
        for (uint32_t rank : grid_.ranks(f, share)) {
            const Aabb& b = grid_.bounds(rank);
            const uint32_t kx0 = gridCell(b.min.x - margin, o.x, invCluster, perSide);
            const uint32_t kx1 = gridCell(b.max.x + margin, o.x, invCluster, perSide);
            const uint32_t ky0 = gridCell(b.min.y - margin, o.y, invCluster, perSide);
            const uint32_t ky1 = gridCell(b.max.y + margin, o.y, invCluster, perSide);
            for (uint32_t ky = ky0; ky <= ky1; ++ky)
                for (uint32_t kx = kx0; kx <= kx1; ++kx) {
                    const uint32_t k = ky * perSide + kx;
                    const gpu::PlantCluster& cluster = field.clusters[k];
                    if (cluster.range.y == 0) continue;
                    if (!b.overlaps({glm::vec3(cluster.boundsMin), glm::vec3(cluster.boundsMax)})) continue;
                    const glm::vec2 origin = field.origin + clusterSize * glm::vec2(float(kx), float(ky));
                    // Stems are vertical, so only plants whose base lies in the collider's xy footprint can be
                    // touched. Clamping keeps the cell range conservative for plants that a rounding put on the
                    // cluster's edge.
                    const uint32_t x0 = gridCell(b.min.x, origin.x, invCell.x, kCellsX);
                    const uint32_t x1 = gridCell(b.max.x, origin.x, invCell.x, kCellsX);
                    const uint32_t y0 = gridCell(b.min.y, origin.y, invCell.y, kCellsY);
                    const uint32_t y1 = gridCell(b.max.y, origin.y, invCell.y, kCellsY);
                    for (uint32_t cy = y0; cy <= y1; ++cy) {
                        const uint32_t row = k * kCellsX * kCellsY + cy * kCellsX;
                        __builtin_prefetch(&index.cellStart[row + x0]);
                        __builtin_prefetch(&index.cellStart[row + x1 + 1]);
                        runs.push_back({rank, row + x0, row + x1 + 1}); // cell offsets; stem offsets below
                    }
                }
        }
    // The cell offsets were prefetched above: turn them into stem ranges, and start fetching the first stems.
    size_t kept = 0;
    for (const Run& cells : runs) {
        const uint32_t begin = index.cellStart[cells.begin], end = index.cellStart[cells.end];
        if (begin == end) continue;
        if (kept < kPrefetchRuns) prefetchStems(index.stems, begin, end);
        runs[kept++] = {cells.rank, begin, end};
    }
    runs.resize(kept);
}

namespace {

// What a collider's hull can reach in the xy plane: its box and, for a sphere, its disc (r2 = +inf otherwise).
struct Footprint {
    float minX, minY, maxX, maxY, centreX, centreY, r2;
};

// Bit j set when stem j of the four at `stems` lies in the footprint's box and strictly inside its disc: a
// branch-free rejection of most tested stems. It rejects only stems the exact test below rejects too: that test's
// squared distance adds dz * dz >= 0 to the same dx * dx + dy * dy, and a rounded sum never falls below a summand.
inline uint32_t footprintMask4(const TileCollisionIndex::Stem* stems, const Footprint& f) {
#if defined(__SSE2__)
    const float* p = &stems->x;
    const __m128 s0 = _mm_loadu_ps(p), s1 = _mm_loadu_ps(p + 4), s2 = _mm_loadu_ps(p + 8), s3 = _mm_loadu_ps(p + 12);
    const __m128 a = _mm_unpacklo_ps(s0, s1), b = _mm_unpacklo_ps(s2, s3); // x0 x1 y0 y1, x2 x3 y2 y3
    const __m128 x = _mm_movelh_ps(a, b), y = _mm_movehl_ps(b, a);
    const __m128 inX = _mm_and_ps(_mm_cmpge_ps(x, _mm_set1_ps(f.minX)), _mm_cmple_ps(x, _mm_set1_ps(f.maxX)));
    const __m128 inY = _mm_and_ps(_mm_cmpge_ps(y, _mm_set1_ps(f.minY)), _mm_cmple_ps(y, _mm_set1_ps(f.maxY)));
    const __m128 dx = _mm_sub_ps(x, _mm_set1_ps(f.centreX)), dy = _mm_sub_ps(y, _mm_set1_ps(f.centreY));
    const __m128 d2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy));
    return uint32_t(_mm_movemask_ps(_mm_and_ps(_mm_and_ps(inX, inY), _mm_cmplt_ps(d2, _mm_set1_ps(f.r2)))));
#else
    uint32_t mask = 0;
    for (uint32_t j = 0; j < 4; ++j) {
        const float x = stems[j].x, y = stems[j].y, dx = x - f.centreX, dy = y - f.centreY;
        const bool in = x >= f.minX && x <= f.maxX && y >= f.minY && y <= f.maxY && dx * dx + dy * dy < f.r2;
        mask |= uint32_t(in) << j;
    }
    return mask;
#endif
}

#if defined(__SSE2__)
inline __m128 select(__m128 condition, __m128 a, __m128 b) {
    return _mm_or_ps(_mm_and_ps(condition, a), _mm_andnot_ps(condition, b));
}

// A sphere collider (Push, Gust, Mower) for sphereLanes4: its numbers broadcast to four lanes once per collider
// rather than per group (the compiler reloads them after every store into the plants' sums, which it cannot prove
// do not alias them), and its response per category: gain * force, and the bend beyond which it fells (fells: a
// Push collider fells by its force alone, -INFINITY, or by bending beyond maxBend; other kinds never, INFINITY).
struct SphereRun {
    __m128 minX, maxX, minY, maxY, centreX, centreY, centreZ, r2, radius, zMin, zMax, maxPush, fellBend;
    std::array<float, gpu::kMaxPlantCategories> gainForce, fellAbove;

    SphereRun(const Collider& c, const Aabb& b, const InteractionParams& params) {
        minX = _mm_set1_ps(b.min.x), maxX = _mm_set1_ps(b.max.x), minY = _mm_set1_ps(b.min.y);
        maxY = _mm_set1_ps(b.max.y), zMin = _mm_set1_ps(b.min.z), zMax = _mm_set1_ps(b.max.z);
        centreX = _mm_set1_ps(c.centre.x), centreY = _mm_set1_ps(c.centre.y), centreZ = _mm_set1_ps(c.centre.z);
        r2 = _mm_set1_ps(c.radius * c.radius), radius = _mm_set1_ps(c.radius);
        maxPush = _mm_set1_ps(kMaxPush), fellBend = _mm_set1_ps(params.recovery.fellBend);
        for (uint32_t k = 0; k < gpu::kMaxPlantCategories; ++k) {
            const CategoryInteraction& response = params.categories[k];
            gainForce[k] = response.pushGain * c.force; // bend's first product (bendOf)
            fellAbove[k] = c.kind != ColliderKind::Push   ? INFINITY
                           : c.force > response.fellForce ? -INFINITY // any bend, a plant in contact being finite
                                                          : response.maxBend;
        }
    }
};

// Four stems against a sphere: touchStem's tests and touchResponse's push (bend = gain * force * depth / height,
// fells, the kMaxPush clamp) four plants at a time, the square roots and divisions of a plant in contact being most
// of the pass. Every lane performs the scalar code's operations in its order, each correctly rounded, so the bits
// are the same. Bit j of `hits` is set when stem j (of those in `valid`) lies in the footprint's box and the
// sphere's reach by its squared distance; it is touched when bit j of `inside` is set too (the square root's test,
// which a rounding can flip at the surface). The loop over `hits` must not wait for the square root: its branches
// would then be decided only after the longest chain of the group. The box and disc test comes first and alone:
// most groups end there.
struct SphereLanes {
    alignas(16) float pushX[4], pushY[4], height[4];
    alignas(16) uint32_t kind[4]; // kContactFell or kContactPush (a mower's cut is the caller's: mowerCut)
    uint32_t hits = 0, inside = 0;
};

inline bool sphereLanes4(const TileCollisionIndex::Stem* stems, uint32_t valid, const SphereRun& c,
                         const float* heights, SphereLanes& out) {
    const float* p = &stems->x;
    const __m128 s0 = _mm_loadu_ps(p), s1 = _mm_loadu_ps(p + 4), s2 = _mm_loadu_ps(p + 8), s3 = _mm_loadu_ps(p + 12);
    const __m128 a = _mm_unpacklo_ps(s0, s1), e = _mm_unpacklo_ps(s2, s3); // x0 x1 y0 y1, x2 x3 y2 y3
    const __m128 x = _mm_movelh_ps(a, e), y = _mm_movehl_ps(e, a);
    const __m128 dx = _mm_sub_ps(x, c.centreX), dy = _mm_sub_ps(y, c.centreY);
    const __m128 xy2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy));
    const __m128 inX = _mm_and_ps(_mm_cmpge_ps(x, c.minX), _mm_cmple_ps(x, c.maxX));
    const __m128 inY = _mm_and_ps(_mm_cmpge_ps(y, c.minY), _mm_cmple_ps(y, c.maxY));
    // The disc: dz * dz >= 0 is added to the same xy2 below, and a rounded sum never falls below a summand.
    const uint32_t footprint =
        valid & uint32_t(_mm_movemask_ps(_mm_and_ps(_mm_and_ps(inX, inY), _mm_cmplt_ps(xy2, c.r2))));
    if (footprint == 0) return false;

    alignas(16) float gainForce[4], fellAbove[4];
    for (uint32_t j = 0; j < 4; ++j) {
        const uint32_t category = stems[j].category();
        out.height[j] = heights[stems[j].shape()];
        gainForce[j] = c.gainForce[category];
        fellAbove[j] = c.fellAbove[category];
    }
    const __m128 z = _mm_movelh_ps(_mm_unpackhi_ps(s0, s1), _mm_unpackhi_ps(s2, s3));
    const __m128 height = _mm_load_ps(out.height), top = _mm_add_ps(z, height);
    // std::clamp(centre.z, z, top): below z -> z, else above top -> top.
    const __m128 qz = select(_mm_cmplt_ps(c.centreZ, z), z, select(_mm_cmplt_ps(top, c.centreZ), top, c.centreZ));
    const __m128 dz = _mm_sub_ps(qz, c.centreZ);
    const __m128 d2 = _mm_add_ps(xy2, _mm_mul_ps(dz, dz));
    const __m128 in =
        _mm_and_ps(_mm_and_ps(_mm_cmple_ps(z, c.zMax), _mm_cmpge_ps(top, c.zMin)), _mm_cmplt_ps(d2, c.r2));
    out.hits = footprint & uint32_t(_mm_movemask_ps(in));
    if (out.hits == 0) return false;
    const __m128 sd = _mm_sub_ps(_mm_sqrt_ps(d2), c.radius);
    out.inside = uint32_t(_mm_movemask_ps(_mm_cmplt_ps(sd, _mm_setzero_ps())));
    const __m128 depth = _mm_xor_ps(sd, _mm_set1_ps(-0.0f));
    const __m128 bend = _mm_div_ps(_mm_mul_ps(_mm_load_ps(gainForce), depth), height);
    const __m128 fell = _mm_cmpgt_ps(bend, _mm_load_ps(fellAbove));
    const __m128i push = _mm_set1_epi32(int32_t(gpu::kContactPush));
    const __m128i fellKind = _mm_set1_epi32(int32_t(gpu::kContactFell ^ gpu::kContactPush));
    _mm_store_si128(reinterpret_cast<__m128i*>(out.kind),
                    _mm_xor_si128(push, _mm_and_si128(_mm_castps_si128(fell), fellKind)));
    // awayDirection: (dx, dy) / sqrt(len2), or (1, 0) on the axis; then touchResponse's push: fellBend when the
    // plant falls, else the bend clamped to kMaxPush (std::min(bend, kMaxPush) is minps(kMaxPush, bend)).
    const __m128 len = _mm_sqrt_ps(xy2), away = _mm_cmpgt_ps(xy2, _mm_set1_ps(1e-12f));
    const __m128 dirX = select(away, _mm_div_ps(dx, len), _mm_set1_ps(1.0f));
    const __m128 dirY = select(away, _mm_div_ps(dy, len), _mm_setzero_ps());
    const __m128 scale = select(fell, c.fellBend, _mm_min_ps(c.maxPush, bend));
    _mm_store_ps(out.pushX, _mm_mul_ps(dirX, scale));
    _mm_store_ps(out.pushY, _mm_mul_ps(dirY, scale));
    return true;
}
#endif

} // namespace

// How collider c touches stem p (kind 0: not at all). Spheres (the common case: gusts, wheels seen from far, feet)
// are rejected with one squared distance before the general hull test.
PlantTouch CollisionPass::touchStem(const Collider& c, const Aabb& b, const TileCollisionIndex::Stem& p) const {
    if (p.x < b.min.x || p.x > b.max.x || p.y < b.min.y || p.y > b.max.y || p.z > b.max.z) return {};
    const float height = index_.heights()[p.shape()];
    if (p.z + height < b.min.z) return {};
    const CategoryInteraction& response = params_.categories[p.category()];
    if (c.shape != ColliderShape::Sphere) return touchPlant(c, {p.x, p.y, p.z}, height, response, params_.recovery);
    // touchPlant for a sphere, with the distance it computes (glm::length: sqrt of (x*x + y*y) + z*z) shared with
    // the rejection test.
    const float qz = std::clamp(c.centre.z, p.z, p.z + height);
    const float dx = p.x - c.centre.x, dy = p.y - c.centre.y, dz = qz - c.centre.z;
    const float d2 = dx * dx + dy * dy + dz * dz;
    if (d2 >= c.radius * c.radius) return {};
    const float sd = std::sqrt(d2) - c.radius;
    if (!(sd < 0.0f)) return {};
    return touchResponse(c, bendOf(c, {p.x, p.y, qz}, -sd, height, response), awayDirection({dx, dy}), height,
                         response, params_.recovery);
}

// Step 2: test the stems of every run, four at a time; touches accumulate per plant in run (= rank) order. Returns
// the stems tested.
uint64_t CollisionPass::touchStems(const TileCollisionIndex::Field& index, uint32_t plantCount,
                                   std::span<const Collider> colliders, std::span<const Run> runs,
                                   Scratch& s) const {
    if (s.sums.size() < plantCount) s.sums.resize(plantCount);
    if (s.touched.size() * 64 < plantCount) s.touched.resize(plantCount / 64 + 1, 0);
    const TileCollisionIndex::Stem* stems = index.stems;
    uint64_t tested = 0;
#if defined(__SSE2__)
    std::optional<SphereRun> sphereRun;
    uint32_t sphereRank = ~0u;
    SphereLanes lanes;
#endif
    for (size_t r = 0; r < runs.size(); ++r) {
        if (r + kPrefetchRuns < runs.size())
            prefetchStems(stems, runs[r + kPrefetchRuns].begin, runs[r + kPrefetchRuns].end);
        const Run run = runs[r];
        tested += run.end - run.begin;
        const Aabb& b = grid_.bounds(run.rank);
        const Collider& c = colliders[grid_.inputIndex(run.rank)];
        const bool sphere = c.shape == ColliderShape::Sphere;
        // Groups of four may read up to three stems past the run (the index pads its end): their bits are dropped.
        auto add = [&](uint32_t plant, const PlantTouch& t) {
            uint64_t& word = s.touched[plant >> 6];
            const uint64_t bit = uint64_t(1) << (plant & 63);
            s.touchedPlants += (word & bit) == 0 ? 1u : 0u;
            word |= bit;
            s.sums[plant].add(t);
        };
#if defined(__SSE2__)
        if (sphere && c.kind != ColliderKind::Downwash) {
            // A collider's runs come one after another (findCellRuns): its lanes are set up at its first.
            if (run.rank != sphereRank) sphereRun.emplace(c, b, params_), sphereRank = run.rank;
            const bool mower = c.kind == ColliderKind::Mower;
            auto test = [&](uint32_t i, uint32_t valid) {
                if (!sphereLanes4(stems + i, valid, *sphereRun, index_.heights(), lanes)) return;
                for (uint32_t hits = lanes.hits; hits != 0; hits &= hits - 1) {
                    const uint32_t j = uint32_t(std::countr_zero(hits));
                    if ((lanes.inside >> j & 1u) == 0) continue;
                    PlantTouch t;
                    t.push = {lanes.pushX[j], lanes.pushY[j]};
                    t.kind = lanes.kind[j];
                    if (mower && t.kind == gpu::kContactPush) mowerCut(c, lanes.height[j], t);
                    add(stems[i + j].plant(), t);
                }
            };
            uint32_t i = run.begin;
            for (; i + 4 <= run.end; i += 4) test(i, 15u);
            if (i < run.end) test(i, (1u << (run.end - i)) - 1u);
            continue;
        }
#endif
        const Footprint footprint{b.min.x,
                                  b.min.y,
                                  b.max.x,
                                  b.max.y,
                                  sphere ? c.centre.x : 0.0f,
                                  sphere ? c.centre.y : 0.0f,
                                  sphere ? c.radius * c.radius : INFINITY};
        for (uint32_t i = run.begin; i < run.end; i += 4) {
            uint32_t mask = footprintMask4(stems + i, footprint);
            if (run.end - i < 4) mask &= (1u << (run.end - i)) - 1u;
            for (; mask != 0; mask &= mask - 1) {
                const TileCollisionIndex::Stem& p = stems[i + uint32_t(std::countr_zero(mask))];
                const PlantTouch t = touchStem(c, b, p);
                if (t.kind != 0) add(p.plant(), t);
            }
        }
    }
    return tested;
}

// Step 3: contacts leave sorted by plant, which is also cluster order (records are ordered by cluster); the bits
// and sums are reset for the next field.
void CollisionPass::emitContacts(uint32_t f, const FieldVegetation& field, Scratch& s, FieldOutput& out) const {
    const uint32_t plantCount = field.plantCount();
    ContactBuffers& buffers = *writing_;
    if (buffers.room[f] < s.touchedPlants) {
        buffers.field[f] = std::make_unique_for_overwrite<gpu::PlantContact[]>(s.touchedPlants);
        buffers.room[f] = s.touchedPlants;
    }
    gpu::PlantContact* contact = buffers.field[f].get();
    uint32_t k = 0, clusterEnd = field.clusters[0].range.x + field.clusters[0].range.y, listed = ~0u;
    for (uint32_t word = 0; word * 64 < plantCount; ++word) {
        uint64_t bits = s.touched[word];
        if (bits == 0) continue;
        s.touched[word] = 0;
        for (; bits != 0; bits &= bits - 1) {
            const uint32_t plant = word * 64 + uint32_t(std::countr_zero(bits));
            TouchSum& sum = s.sums[plant];
            *contact = sum.contact(params_.recovery);
            contact->plant = field.firstPlant + plant;
            contact->field = f;
            ++contact;
            sum = TouchSum{};
            while (plant >= clusterEnd) {
                ++k;
                clusterEnd = field.clusters[k].range.x + field.clusters[k].range.y;
            }
            if (k != listed) out.clusters.push_back(field.firstCluster + k);
            listed = k;
        }
    }
    out.contactCount = s.touchedPlants;
    s.touchedPlants = 0;
}

// Every field into its own output slot, on the pool's threads.
void CollisionPass::collideFields(std::span<const Collider> colliders) {
    for (FieldOutput& o : outputs_) {
        o.contactCount = 0;
        o.clusters.clear();
        o.clustersTested = 0;
        o.plantsTested = 0;
        o.tested = false;
    }
    if (grid_.size() == 0) return;
    const uint32_t fieldCount = uint32_t(outputs_.size());
    if (scratch_.size() < pool_->threads()) scratch_.resize(pool_->threads());
    // Tasks of a few consecutive fields: one field's runs are found, and their stems fetched, while the previous
    // field's are tested (the plant index is far larger than the caches). The colliders are binned into the fields
    // first, a share per thread, in the same run of the pool: a second wake-up of the helpers costs what it saves.
    const uint32_t tasks = (fieldCount + kFieldsPerTask - 1) / kFieldsPerTask;
    const ParallelBody binShare = [&](uint32_t share, uint32_t) { grid_.binShare(share); };
    pool_->run(grid_.shares(), binShare, tasks, [&](uint32_t task, uint32_t worker) {
        Scratch& s = scratch_[worker];
        const uint32_t first = task * kFieldsPerTask, last = std::min(first + kFieldsPerTask, fieldCount);
        bool pending = false;
        for (uint32_t f = first; f <= last; ++f) {
            const bool ready = f < last && prepareField(f, s, f & 1u, outputs_[f]);
            if (pending) finishField(f - 1, colliders, s, (f - 1) & 1u, outputs_[f - 1]);
            pending = ready;
        }
    });
}

// The field slots in field order: the result is the same for any thread count and schedule. The contacts stay in
// the buffers their fields wrote (TickContacts): only their runs are listed here.
CollisionResult CollisionPass::gatherFields(std::span<const Collider> colliders) const {
    CollisionResult result;
    result.stats.colliders = uint32_t(colliders.size());
    result.stats.collidersKept = grid_.size();
    std::vector<TickContacts::Run> runs;
    for (uint32_t f = 0; f < uint32_t(outputs_.size()); ++f) {
        const FieldOutput& o = outputs_[f];
        result.stats.fieldsTested += o.tested ? 1u : 0u;
        result.stats.clustersTested += o.clustersTested;
        result.stats.plantsTested += o.plantsTested;
        if (o.contactCount == 0) continue;
        runs.emplace_back(writing_->field[f].get(), o.contactCount);
        result.touchedFields.push_back(f);
        result.touchedClusters.insert(result.touchedClusters.end(), o.clusters.begin(), o.clusters.end());
    }
    result.contacts = TickContacts(writing_, std::move(runs));
    result.stats.contactBytes = uint64_t(result.contacts.size()) * sizeof(gpu::PlantContact);
    return result;
}

// A set of buffers that no earlier result holds, to write this tick's contacts into. Two sets are kept for their
// room; a caller that keeps more ticks' contacts than that keeps the sets they lie in alive itself.
void CollisionPass::takeFreeBuffers() {
    constexpr size_t kKeptSets = 2;
    writing_.reset();
    for (const std::shared_ptr<ContactBuffers>& set : buffers_)
        if (set.use_count() == 1) {
            writing_ = set;
            return;
        }
    if (buffers_.size() == kKeptSets) buffers_.pop_back();
    writing_ = buffers_.emplace_back(std::make_shared<ContactBuffers>(outputs_.size()));
}

CollisionResult CollisionPass::run(std::span<const Collider> colliders, uint32_t threads) {
    assert(threads >= 1);
    const uint32_t fieldCount = uint32_t(outputs_.size());
    const uint32_t used = std::min(threads, std::max((fieldCount + kFieldsPerTask - 1) / kFieldsPerTask, 1u));
    if (!pool_ || pool_->threads() != used) {
        pool_.reset();
        pool_ = std::make_unique<ParallelFor>(used);
    }
    takeFreeBuffers();
    const Stopwatch total;
    grid_.begin(colliders, index_.bounds(), pool_->threads());
    const double buildMs = total.ms();
    collideFields(colliders);
    const Stopwatch merge;
    CollisionResult result = gatherFields(colliders);
    result.stats.buildMs = buildMs;
    result.stats.mergeMs = merge.ms();
    result.stats.cpuMs = total.ms();
    return result;
}

} // namespace sward
