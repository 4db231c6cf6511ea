#include "interaction/collision.h"

#include "vegetation/records.h"

#include "common/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <thread>

#include <sys/mman.h>

namespace sward {

namespace {

// snorm16 with round half away from zero, exactly as recovery.cpp / recovery.glsl unpack it.
uint32_t packSnorm16(float v) {
    float s = std::clamp(v, -1.0f, 1.0f) * 32767.0f;
    int32_t q = s >= 0.0f ? int32_t(s + 0.5f) : -int32_t(-s + 0.5f);
    return uint32_t(q) & 0xffffu;
}

constexpr float kMaxPush = 0.95f; // a bend of 1 would lay the tip on the ground: leave that to felled plants

double numberAt(const nlohmann::json& v, const std::string& source, const std::string& key, double lo, double hi) {
    require(v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= lo && v.get<double>() <= hi,
            source + ": interaction '" + key + "' must be a number in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
    return v.get<double>();
}

void requireObject(const nlohmann::json& v, const std::string& source, const std::string& key) {
    require(v.is_object(), source + ": interaction '" + key + "' must be an object");
}

} // namespace

InteractionParams parseInteractionParams(const nlohmann::json& json, const std::string& source) {
    InteractionParams p;
    requireObject(json, source, "interaction");
    for (const auto& [key, value] : json.items()) {
        if (key == "categories") {
            require(value.is_array() && !value.empty() && value.size() <= gpu::kMaxPlantCategories,
                    source + ": interaction 'categories' must be an array of 1 to 4 objects");
            for (size_t i = 0; i < value.size(); ++i) {
                const std::string prefix = "categories[" + std::to_string(i) + "].";
                requireObject(value[i], source, prefix.substr(0, prefix.size() - 1));
                for (const auto& [k, v] : value[i].items()) {
                    if (k == "fell_force")
                        p.categories[i].fellForce = float(numberAt(v, source, prefix + k, 0.0, 1e6));
                    else if (k == "push_gain")
                        p.categories[i].pushGain = float(numberAt(v, source, prefix + k, 0.0, 1000.0));
                    else
                        throw Error(source + ": unknown interaction key '" + prefix + k + "'");
                }
            }
        } else if (key == "recovery") {
            requireObject(value, source, "recovery");
            RecoveryParams& r = p.recovery;
            for (const auto& [k, v] : value.items()) {
                const std::string name = "recovery." + k;
                if (k == "time_step") {
                    r.timeStep = float(numberAt(v, source, name, 1e-6, 1.0));
                } else if (k == "stiffness") {
                    r.stiffness = float(numberAt(v, source, name, 0.0, 1e6));
                } else if (k == "damping") {
                    r.damping = float(numberAt(v, source, name, 0.0, 1e6));
                } else if (k == "rest_bend") {
                    r.restBend = float(numberAt(v, source, name, 0.0, 0.5));
                } else if (k == "fell_bend") {
                    r.fellBend = float(numberAt(v, source, name, 0.0, kMaxPush));
                } else if (k == "rest_ticks") {
                    require(v.is_number_unsigned() && v.get<uint64_t>() >= 1 && v.get<uint64_t>() <= 1000000,
                            source + ": interaction '" + name + "' must be an integer in [1, 1000000]");
                    r.restTicks = v.get<uint32_t>();
                } else {
                    throw Error(source + ": unknown interaction key '" + name + "'");
                }
            }
        } else {
            throw Error(source + ": unknown interaction key '" + key + "'");
        }
    }
    return p;
}

// --- BVH ---------------------------------------------------------------------------------------------------------

void ColliderBvh::build(std::span<const Collider> colliders, const Aabb& keep) {
    std::vector<Kept>& kept = kept_;
    kept.clear();
    // Colliders far from any plant (high above, off the tile) are dropped before sorting: they are the bulk of a
    // large scene and must cost one box test each.
    for (uint32_t i = 0; i < colliders.size(); ++i) {
        Aabb b = worldBounds(colliders[i]);
        if (b.overlaps(keep)) kept.push_back({colliders[i].id, i, b});
    }
    // Callers usually list colliders in id order already: then the O(n) check is all this costs.
    auto byId = [](const Kept& a, const Kept& b) { return a.id != b.id ? a.id < b.id : a.input < b.input; };
    if (!std::is_sorted(kept.begin(), kept.end(), byId)) std::sort(kept.begin(), kept.end(), byId);
    const uint32_t n = uint32_t(kept.size());
    input_.resize(n);
    bounds_.resize(n);
    for (uint32_t r = 0; r < n; ++r) {
        input_[r] = kept[r].input;
        bounds_[r] = kept[r].box;
    }
    items_.clear();
    nodes_.clear();
    if (n == 0) return;
    // Linear BVH: ranks sorted along a Morton curve of their xy centres (vegetation is flat, so xy carries the
    // locality), leaves of 4 consecutive colliders, then pairs of consecutive nodes merged level by level. The
    // keys hold the rank below the code, so the order is total and the tree deterministic; O(n) after one sort.
    glm::vec2 lo(bounds_[0].min), hi(bounds_[0].max);
    for (const Aabb& box : bounds_) {
        lo = glm::min(lo, glm::vec2(box.min + box.max) * 0.5f);
        hi = glm::max(hi, glm::vec2(box.min + box.max) * 0.5f);
    }
    const glm::vec2 scale = 65535.0f / glm::max(hi - lo, glm::vec2(1e-6f));
    auto spread = [](uint64_t v) { // 16 bits -> every other bit of 32
        v = (v | (v << 8)) & 0x00ff00ffull;
        v = (v | (v << 4)) & 0x0f0f0f0full;
        v = (v | (v << 2)) & 0x33333333ull;
        return (v | (v << 1)) & 0x55555555ull;
    };
    std::vector<uint64_t>& keys = keys_;
    keys.resize(n);
    for (uint32_t r = 0; r < n; ++r) {
        glm::vec2 c = (glm::vec2(bounds_[r].min + bounds_[r].max) * 0.5f - lo) * scale;
        uint64_t qx = uint64_t(std::clamp(c.x, 0.0f, 65535.0f)), qy = uint64_t(std::clamp(c.y, 0.0f, 65535.0f));
        keys[r] = ((spread(qx) | (spread(qy) << 1)) << 32) | r;
    }
    // LSD radix sort of the 32-bit codes, 8 bits per pass. Stable and started in rank order, so it gives exactly
    // the order of sorting the whole keys (ties by rank), in O(n).
    keysTmp_.resize(n);
    for (uint32_t shift = 32; shift < 64; shift += 8) {
        uint32_t count[257] = {};
        for (uint64_t k : keys) ++count[((k >> shift) & 255u) + 1];
        for (uint32_t b = 1; b < 257; ++b) count[b] += count[b - 1];
        for (uint64_t k : keys) keysTmp_[count[(k >> shift) & 255u]++] = k;
        keys.swap(keysTmp_);
    }
    items_.resize(n);
    for (uint32_t i = 0; i < n; ++i) items_[i] = uint32_t(keys[i]);

    constexpr uint32_t kLeaf = 4;
    nodes_.reserve(2 * (n / kLeaf + 1) + 64);
    uint32_t levelBegin = 0;
    for (uint32_t first = 0; first < n; first += kLeaf) {
        Node leaf{bounds_[items_[first]], first, std::min(kLeaf, n - first)};
        for (uint32_t i = first; i < first + leaf.count; ++i) {
            leaf.box.min = glm::min(leaf.box.min, bounds_[items_[i]].min);
            leaf.box.max = glm::max(leaf.box.max, bounds_[items_[i]].max);
        }
        nodes_.push_back(leaf);
    }
    uint32_t levelEnd = uint32_t(nodes_.size());
    // Each level is contiguous in nodes_, so the two children of a parent are always neighbours; an odd last node
    // is copied up unchanged.
    while (levelEnd - levelBegin > 1) {
        for (uint32_t i = levelBegin; i < levelEnd; i += 2) {
            if (i + 1 == levelEnd) {
                Node copy = nodes_[i];
                nodes_.push_back(copy);
                continue;
            }
            Aabb box{glm::min(nodes_[i].box.min, nodes_[i + 1].box.min),
                     glm::max(nodes_[i].box.max, nodes_[i + 1].box.max)};
            nodes_.push_back({box, i, 0});
        }
        levelBegin = levelEnd;
        levelEnd = uint32_t(nodes_.size());
    }
    root_ = levelBegin;
}

void ColliderBvh::query(const Aabb& box, std::vector<uint32_t>& ranks) const {
    if (nodes_.empty()) return;
    const size_t first = ranks.size();
    uint32_t stack[64];
    uint32_t top = 0;
    stack[top++] = root_;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (!node.box.overlaps(box)) continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                if (bounds_[items_[i]].overlaps(box)) ranks.push_back(items_[i]);
        } else {
            stack[top++] = node.first;
            stack[top++] = node.first + 1;
        }
    }
    std::sort(ranks.begin() + first, ranks.end());
}

// --- Plant index -------------------------------------------------------------------------------------------------

void TileCollisionIndex::Free::operator()(void* p) const { std::free(p); }

TileCollisionIndex::TileCollisionIndex(const VegetationTile& tile, const VegetationParams& params) {
    constexpr uint32_t kCells = kCellsPerSide * kCellsPerSide;
    cellSize_ = tile.clusterSize / float(kCellsPerSide);
    for (uint32_t category = 0; category < 4; ++category)
        for (uint32_t size = 0; size < 256; ++size)
            heights_[category | size << 2] = params.categories[category].height * float(size) / gpu::kPlantSizeDivisor;
    size_t total = 0, totalCells = 0;
    for (const FieldVegetation& field : tile.fields) {
        require(field.plantCount() <= kMaxFieldPlants,
                "a field holds " + std::to_string(field.plantCount()) + " plants; the collision pass supports at most " +
                    std::to_string(kMaxFieldPlants) + " per field (use smaller fields)");
        total += field.plantCount();
        totalCells += field.clusters.size() * kCells + 1;
    }
    // One block for every stem and then every cell offset, 2 MiB aligned so the kernel can back it with
    // transparent huge pages: a tick touches a few lines in each of hundreds of fields, and a TLB miss per field
    // (4 KiB pages, nested paging in a VM) costs as much as the lines themselves.
    constexpr size_t kHuge = size_t(2) << 20;
    const size_t used = total * sizeof(Stem) + totalCells * sizeof(uint32_t);
    const size_t bytes = std::max<size_t>((used + kHuge - 1) / kHuge * kHuge, kHuge);
    stems_.reset(static_cast<Stem*>(std::aligned_alloc(kHuge, bytes)));
    require(stems_ != nullptr, "out of memory for the collision index (" + std::to_string(bytes) + " bytes)");
#ifdef MADV_HUGEPAGE
    madvise(stems_.get(), bytes, MADV_HUGEPAGE); // a hint: without huge pages the pass is only slower
#endif

    fields_.resize(tile.fields.size());
    bool any = false;
    std::vector<uint32_t> cellOf, fill;
    size_t first = 0;
    uint32_t* cells = reinterpret_cast<uint32_t*>(stems_.get() + total);
    for (size_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        Field& out = fields_[f];
        const uint32_t n = field.plantCount();
        Stem* stems = stems_.get() + first;
        out.stems = stems;
        first += n;
        const std::span<uint32_t> cellStart(cells, field.clusters.size() * kCells + 1);
        cells += cellStart.size();
        std::fill(cellStart.begin(), cellStart.end(), 0u);
        out.cellStart = cellStart.data();
        cellOf.resize(n);
        for (uint32_t k = 0; k < field.clusters.size(); ++k) {
            const gpu::PlantCluster& cluster = field.clusters[k];
            out.clustersWithPlants += cluster.range.y > 0 ? 1u : 0u;
            glm::vec2 origin = field.origin + tile.clusterSize * glm::vec2(float(k % tile.clustersPerField),
                                                                           float(k / tile.clustersPerField));
            if (cluster.range.y > 0) {
                glm::vec2 below = origin - glm::vec2(cluster.boundsMin);
                glm::vec2 above = glm::vec2(cluster.boundsMax) - (origin + tile.clusterSize);
                out.overhang = std::max({out.overhang, below.x, below.y, above.x, above.y});
            }
            for (uint32_t i = cluster.range.x; i < cluster.range.x + cluster.range.y; ++i) {
                glm::vec3 p = decodePlantPosition(field.staticRecords[i], field.origin, field.positionStep);
                auto cell = [&](float v, float o) {
                    return uint32_t(
                        std::clamp(int32_t(std::floor((v - o) / cellSize_)), 0, int32_t(kCellsPerSide) - 1));
                };
                cellOf[i] = k * kCells + cell(p.y, origin.y) * kCellsPerSide + cell(p.x, origin.x);
                ++cellStart[cellOf[i] + 1];
            }
        }
        for (size_t c = 1; c < cellStart.size(); ++c) cellStart[c] += cellStart[c - 1];
        // Counting sort in record order: within a cell plants stay in ascending record index.
        fill.assign(cellStart.begin(), cellStart.end() - 1);
        for (uint32_t i = 0; i < n; ++i) {
            const gpu::PlantStatic& record = field.staticRecords[i];
            glm::vec3 p = decodePlantPosition(record, field.origin, field.positionStep);
            uint32_t shape = (record.attributes & 3u) | (record.attributes >> 24) << 2;
            stems[fill[cellOf[i]]++] = {p.x, p.y, p.z, i | shape << 22};
        }
        if (n == 0) continue;
        if (!any) bounds_ = {field.boundsMin, field.boundsMax};
        bounds_.min = glm::min(bounds_.min, field.boundsMin);
        bounds_.max = glm::max(bounds_.max, field.boundsMax);
        any = true;
    }
    if (!any) bounds_ = {glm::vec3(INFINITY), glm::vec3(-INFINITY)}; // overlaps nothing
}

// --- Per plant ---------------------------------------------------------------------------------------------------

namespace {

// A stem exactly on the axis has no "away": any fixed direction keeps the result deterministic.
inline glm::vec2 awayDirection(glm::vec2 away) {
    float len2 = glm::dot(away, away);
    return len2 > 1e-12f ? away / std::sqrt(len2) : glm::vec2(1.0f, 0.0f);
}

// The response to a penetration `depth` at stem point q, pushing along dir (the rules in collision.h). Shared by
// touchPlant and the pass's sphere path, so both give identical bits.
inline PlantTouch touchResponse(const Collider& c, glm::vec3 q, float depth, glm::vec2 dir, float height,
                                const CategoryInteraction& response, const RecoveryParams& recovery) {
    PlantTouch t;
    float bend = 0.0f;
    switch (c.kind) {
    case ColliderKind::Push:
    case ColliderKind::Gust:
    case ColliderKind::Mower:
        bend = response.pushGain * c.force * depth / height;
        break;
    case ColliderKind::Downwash: {
        float reach = c.centre.z - c.end.z;
        float below = reach > 0.0f ? std::clamp((c.centre.z - q.z) / reach, 0.0f, 1.0f) : 0.0f;
        bend = response.pushGain * c.force * depth / c.radius * (1.0f - 0.5f * below);
        break;
    }
    }
    // Only solid bodies carry weight: air (gusts, downwash) bends, and a mower's weight is on its wheels.
    if (c.kind == ColliderKind::Push && c.force > response.fellForce) {
        t.kind = gpu::kContactFell;
        t.push = dir * recovery.fellBend;
        return t;
    }
    t.push = dir * std::min(bend, kMaxPush);
    t.kind = gpu::kContactPush;
    if (c.kind == ColliderKind::Mower && c.cutHeight < height) {
        t.kind = gpu::kContactCut;
        t.cut = uint32_t(std::clamp(std::floor(255.0f * c.cutHeight / height + 0.5f), 0.0f, 254.0f));
    }
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
    return touchResponse(c, q, -sd, awayDirection({q.x - axis.x, q.y - axis.y}), height, response, recovery);
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
        return {0u, packSnorm16(push.x) | (packSnorm16(push.y) << 16), flags, 0u};
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

// Helper threads that stay alive between ticks: starting two threads per tick costs more than a whole idle tick.
// run(job) runs job(0) on the caller and job(1..helpers) on the helpers, and returns when all have finished.
class CollisionPass::Workers {
public:
    explicit Workers(uint32_t helpers) {
        for (uint32_t i = 0; i < helpers; ++i) threads_.emplace_back([this, i] { loop(i + 1); });
    }
    ~Workers() {
        {
            std::lock_guard lock(mutex_);
            quit_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }
    uint32_t helpers() const { return uint32_t(threads_.size()); }

    void run(const std::function<void(uint32_t)>& job) {
        {
            std::lock_guard lock(mutex_);
            job_ = &job;
            busy_ = uint32_t(threads_.size());
            ++generation_;
        }
        wake_.notify_all();
        job(0);
        std::unique_lock lock(mutex_);
        done_.wait(lock, [&] { return busy_ == 0; });
        job_ = nullptr;
    }

private:
    void loop(uint32_t index) {
        uint64_t seen = 0;
        for (;;) {
            const std::function<void(uint32_t)>* job;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
                if (quit_) return;
                seen = generation_;
                job = job_;
            }
            (*job)(index);
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(uint32_t)>* job_ = nullptr;
    uint64_t generation_ = 0;
    uint32_t busy_ = 0;
    bool quit_ = false;
    std::vector<std::thread> threads_;
};

struct CollisionPass::Scratch {
    static constexpr uint32_t kNone = ~0u;
    // A row of sub-cells under one collider's footprint in one cluster: stems [begin, end) to test.
    struct Run {
        uint32_t rank, begin, end;
    };
    std::vector<uint32_t> candidates;
    std::vector<Run> runs;
    std::vector<uint32_t> slot;    // per plant of the field: its index in sums, or kNone
    std::vector<uint64_t> touched; // per plant of the field, one bit: has a touch (read back in plant order)
    std::vector<TouchSum> sums;
};

CollisionPass::CollisionPass(const VegetationTile& tile, const VegetationParams& vegetation,
                             const InteractionParams& params)
    : tile_(&tile), index_(tile, vegetation), params_(params), outputs_(tile.fields.size()) {}

CollisionPass::~CollisionPass() = default;
CollisionPass::CollisionPass(CollisionPass&&) noexcept = default;
CollisionPass& CollisionPass::operator=(CollisionPass&&) noexcept = default;

namespace {

// Asks for the cache lines of stems [begin, end) ahead of their use.
inline void prefetchStems(const TileCollisionIndex::Stem* stems, uint32_t begin, uint32_t end) {
    const char* p = reinterpret_cast<const char*>(stems + begin);
    const char* e = reinterpret_cast<const char*>(stems + end);
    for (p = reinterpret_cast<const char*>(uintptr_t(p) & ~uintptr_t(63)); p < e; p += 64) __builtin_prefetch(p);
}

} // namespace

void CollisionPass::collideField(uint32_t f, std::span<const Collider> colliders, Scratch& s, FieldOutput& out) const {
    constexpr uint32_t kSide = TileCollisionIndex::kCellsPerSide;
    // Runs prefetched ahead of the one being tested: the plant index is far larger than the caches, and each run
    // is a separate miss that the hardware prefetcher cannot foresee.
    constexpr uint32_t kPrefetchRuns = 48;
    const FieldVegetation& field = tile_->fields[f];
    if (field.plantCount() == 0) return;
    // The cluster table is read for every candidate below: fetch it while the BVH is searched.
    for (size_t offset = 0; offset < field.clusters.size() * sizeof(gpu::PlantCluster); offset += 64)
        __builtin_prefetch(reinterpret_cast<const char*>(field.clusters.data()) + offset);
    s.candidates.clear();
    bvh_.query({field.boundsMin, field.boundsMax}, s.candidates);
    if (s.candidates.empty()) return;
    out.tested = true;
    const TileCollisionIndex::Field& index = index_.field(f);
    out.clustersTested = index.clustersWithPlants;
    const float invCell = 1.0f / index_.cellSize();
    const uint32_t perSide = tile_->clustersPerField;
    const float clusterSize = tile_->clusterSize, invCluster = 1.0f / clusterSize;
    // Cluster boxes may reach a little beyond their grid squares (position rounding, plant extents): the margin
    // keeps the range of clusters visited conservative, the exact cluster box test below decides.
    const float margin = index.overhang + 1e-3f;

    // Phase 1: the runs of stems under each candidate's footprint, candidates in rank (= id) order so each plant's
    // touches are summed in id order. Only clusters under the collider's box are visited.
    s.runs.clear();
    for (uint32_t rank : s.candidates) {
        const Aabb& b = bvh_.bounds(rank);
        auto clusterCell = [&](float v, float o) {
            return uint32_t(std::clamp(int32_t(std::floor((v - o) * invCluster)), 0, int32_t(perSide) - 1));
        };
        const uint32_t kx0 = clusterCell(b.min.x - margin, field.origin.x);
        const uint32_t kx1 = clusterCell(b.max.x + margin, field.origin.x);
        const uint32_t ky0 = clusterCell(b.min.y - margin, field.origin.y);
        const uint32_t ky1 = clusterCell(b.max.y + margin, field.origin.y);
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
                auto cell = [&](float v, float o) {
                    return uint32_t(std::clamp(int32_t(std::floor((v - o) * invCell)), 0, int32_t(kSide) - 1));
                };
                const uint32_t x0 = cell(b.min.x, origin.x), x1 = cell(b.max.x, origin.x);
                const uint32_t y0 = cell(b.min.y, origin.y), y1 = cell(b.max.y, origin.y);
                for (uint32_t cy = y0; cy <= y1; ++cy) {
                    const uint32_t row = k * kSide * kSide + cy * kSide;
                    __builtin_prefetch(&index.cellStart[row + x0]);
                    __builtin_prefetch(&index.cellStart[row + x1 + 1]);
                    s.runs.push_back({rank, row + x0, row + x1 + 1}); // cell offsets; stem offsets below
                }
            }
    }
    // The cell offsets were prefetched above: turn them into stem ranges, and start fetching the first stems.
    size_t kept = 0;
    for (const Scratch::Run& cells : s.runs) {
        const uint32_t begin = index.cellStart[cells.begin], end = index.cellStart[cells.end];
        if (begin == end) continue;
        if (kept < kPrefetchRuns) prefetchStems(index.stems, begin, end);
        s.runs[kept++] = {cells.rank, begin, end};
    }
    s.runs.resize(kept);

    // Phase 2: test the stems of every run; touches accumulate per plant in run (= rank) order.
    const uint32_t plantCount = field.plantCount();
    if (s.slot.size() < plantCount) s.slot.resize(plantCount, Scratch::kNone);
    if (s.touched.size() * 64 < plantCount) s.touched.resize(plantCount / 64 + 1, 0);
    const TileCollisionIndex::Stem* stems = index.stems;
    const float* heights = index_.heights();
    uint64_t tested = 0;
    for (size_t r = 0; r < s.runs.size(); ++r) {
        if (r + kPrefetchRuns < s.runs.size())
            prefetchStems(stems, s.runs[r + kPrefetchRuns].begin, s.runs[r + kPrefetchRuns].end);
        const Scratch::Run run = s.runs[r];
        tested += run.end - run.begin;
        const Aabb& b = bvh_.bounds(run.rank);
        const Collider& c = colliders[bvh_.inputIndex(run.rank)];
        // Spheres (the common case: gusts, wheels seen from far, feet) are rejected with one squared distance
        // before the general hull test.
        const bool sphere = c.shape == ColliderShape::Sphere;
        const float r2 = c.radius * c.radius;
        for (uint32_t i = run.begin; i < run.end; ++i) {
            const TileCollisionIndex::Stem p = stems[i];
            if (p.x < b.min.x || p.x > b.max.x || p.y < b.min.y || p.y > b.max.y || p.z > b.max.z) continue;
            const float height = heights[p.shape()];
            if (p.z + height < b.min.z) continue;
            PlantTouch t;
            if (sphere) {
                // touchPlant for a sphere, with the distance it computes (glm::length: sqrt of (x*x + y*y) + z*z)
                // shared with the rejection test.
                const float qz = std::clamp(c.centre.z, p.z, p.z + height);
                const float dx = p.x - c.centre.x, dy = p.y - c.centre.y, dz = qz - c.centre.z;
                const float d2 = dx * dx + dy * dy + dz * dz;
                if (d2 >= r2) continue;
                const float sd = std::sqrt(d2) - c.radius;
                if (!(sd < 0.0f)) continue;
                t = touchResponse(c, {p.x, p.y, qz}, -sd, awayDirection({dx, dy}), height,
                                  params_.categories[p.category()], params_.recovery);
            } else {
                t = touchPlant(c, {p.x, p.y, p.z}, height, params_.categories[p.category()], params_.recovery);
                if (t.kind == 0) continue;
            }
            const uint32_t plant = p.plant();
            uint32_t& slot = s.slot[plant];
            if (slot == Scratch::kNone) {
                slot = uint32_t(s.sums.size());
                s.touched[plant >> 6] |= uint64_t(1) << (plant & 63);
                s.sums.emplace_back();
            }
            s.sums[slot].add(t);
        }
    }
    out.plantsTested = tested;
    if (s.sums.empty()) return;

    // Contacts leave sorted by plant, which is also cluster order (records are ordered by cluster); the bits and
    // slots are reset for the next field.
    uint32_t k = 0;
    for (uint32_t word = 0; word * 64 < plantCount; ++word) {
        for (uint64_t bits = s.touched[word]; bits != 0; bits &= bits - 1) {
            const uint32_t plant = word * 64 + uint32_t(std::countr_zero(bits));
            uint32_t& slot = s.slot[plant];
            gpu::PlantContact contact = s.sums[slot].contact(params_.recovery);
            contact.plant = field.firstPlant + plant;
            contact.field = f;
            out.contacts.push_back(contact);
            slot = Scratch::kNone;
            while (plant >= field.clusters[k].range.x + field.clusters[k].range.y) ++k;
            if (out.clusters.empty() || out.clusters.back() != field.firstCluster + k)
                out.clusters.push_back(field.firstCluster + k);
        }
        s.touched[word] = 0;
    }
    s.sums.clear();
}

CollisionResult CollisionPass::run(std::span<const Collider> colliders, uint32_t threads) {
    assert(threads >= 1);
    const auto start = std::chrono::steady_clock::now();
    bvh_.build(colliders, index_.bounds());
    const auto built = std::chrono::steady_clock::now();
    for (FieldOutput& o : outputs_) {
        o.contacts.clear();
        o.clusters.clear();
        o.clustersTested = 0;
        o.plantsTested = 0;
        o.tested = false;
    }
    const uint32_t fieldCount = uint32_t(outputs_.size());
    if (bvh_.size() > 0) {
        // Fields are taken from a shared counter (load balance), but each writes only its own slot and the slots
        // are merged in field order below, so the result is the same for any thread count and schedule.
        const uint32_t used = std::min(threads, std::max(fieldCount, 1u));
        if (scratch_.size() < used) scratch_.resize(used);
        std::atomic<uint32_t> next{0};
        std::function<void(uint32_t)> job = [&](uint32_t worker) {
            for (uint32_t f; (f = next.fetch_add(1, std::memory_order_relaxed)) < fieldCount;)
                collideField(f, colliders, scratch_[worker], outputs_[f]);
        };
        if (used == 1) {
            job(0);
        } else {
            if (!workers_ || workers_->helpers() != used - 1) {
                workers_.reset();
                workers_ = std::make_unique<Workers>(used - 1);
            }
            workers_->run(job);
        }
    }
    CollisionResult result;
    result.stats.colliders = uint32_t(colliders.size());
    result.stats.collidersKept = bvh_.size();
    size_t contactCount = 0;
    for (const FieldOutput& o : outputs_) contactCount += o.contacts.size();
    result.contacts.reserve(contactCount);
    for (uint32_t f = 0; f < fieldCount; ++f) {
        const FieldOutput& o = outputs_[f];
        result.stats.fieldsTested += o.tested ? 1u : 0u;
        result.stats.clustersTested += o.clustersTested;
        result.stats.plantsTested += o.plantsTested;
        if (o.contacts.empty()) continue;
        result.touchedFields.push_back(f);
        result.contacts.insert(result.contacts.end(), o.contacts.begin(), o.contacts.end());
        result.touchedClusters.insert(result.touchedClusters.end(), o.clusters.begin(), o.clusters.end());
    }
    result.stats.contactBytes = uint64_t(result.contacts.size()) * sizeof(gpu::PlantContact);
    result.stats.buildMs = std::chrono::duration<double, std::milli>(built - start).count();
    result.stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace sward
