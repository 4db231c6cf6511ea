#include "collision.h"

#include "records.h"

#include "error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <thread>

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
    struct Kept {
        uint32_t id, input;
        Aabb box;
    };
    std::vector<Kept> kept;
    // Colliders far from any plant (high above, off the tile) are dropped before sorting: they are the bulk of a
    // large scene and must cost one box test each.
    for (uint32_t i = 0; i < colliders.size(); ++i) {
        Aabb b = worldBounds(colliders[i]);
        if (b.overlaps(keep)) kept.push_back({colliders[i].id, i, b});
    }
    std::sort(kept.begin(), kept.end(),
              [](const Kept& a, const Kept& b) { return a.id != b.id ? a.id < b.id : a.input < b.input; });
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
    std::vector<uint64_t> keys(n);
    for (uint32_t r = 0; r < n; ++r) {
        glm::vec2 c = (glm::vec2(bounds_[r].min + bounds_[r].max) * 0.5f - lo) * scale;
        uint64_t qx = uint64_t(std::clamp(c.x, 0.0f, 65535.0f)), qy = uint64_t(std::clamp(c.y, 0.0f, 65535.0f));
        keys[r] = ((spread(qx) | (spread(qy) << 1)) << 32) | r;
    }
    std::sort(keys.begin(), keys.end());
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

TileCollisionIndex::TileCollisionIndex(const VegetationTile& tile, const VegetationParams& params) {
    constexpr uint32_t kCells = kCellsPerSide * kCellsPerSide;
    cellSize_ = tile.clusterSize / float(kCellsPerSide);
    fields_.resize(tile.fields.size());
    bool any = false;
    for (size_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        Field& out = fields_[f];
        out.cellStart.assign(field.clusters.size() * kCells + 1, 0u);
        out.plants.resize(field.plantCount());
        std::vector<uint32_t> cellOf(field.plantCount());
        std::vector<Plant> decoded(field.plantCount());
        for (uint32_t k = 0; k < field.clusters.size(); ++k) {
            const gpu::PlantCluster& cluster = field.clusters[k];
            glm::vec2 origin = field.origin + tile.clusterSize * glm::vec2(float(k % tile.clustersPerField),
                                                                           float(k / tile.clustersPerField));
            for (uint32_t i = cluster.range.x; i < cluster.range.x + cluster.range.y; ++i) {
                const gpu::PlantStatic& record = field.staticRecords[i];
                glm::vec3 p = decodePlantPosition(record, field.origin, field.positionStep);
                uint32_t category = record.attributes & 3u;
                // The same expression as placement's cluster bounds, so every stem lies inside its cluster box.
                float height =
                    params.categories[category].height * float(record.attributes >> 24) / gpu::kPlantSizeDivisor;
                decoded[i] = {p.x, p.y, p.z, height, i, category};
                auto cell = [&](float v, float o) {
                    return uint32_t(
                        std::clamp(int32_t(std::floor((v - o) / cellSize_)), 0, int32_t(kCellsPerSide) - 1));
                };
                cellOf[i] = k * kCells + cell(p.y, origin.y) * kCellsPerSide + cell(p.x, origin.x);
                ++out.cellStart[cellOf[i] + 1];
            }
        }
        for (size_t c = 1; c < out.cellStart.size(); ++c) out.cellStart[c] += out.cellStart[c - 1];
        // Counting sort in record order: within a cell plants stay in ascending record index.
        std::vector<uint32_t> fill(out.cellStart.begin(), out.cellStart.end() - 1);
        for (uint32_t i = 0; i < field.plantCount(); ++i) out.plants[fill[cellOf[i]]++] = decoded[i];
        if (field.plantCount() == 0) continue;
        if (!any) bounds_ = {field.boundsMin, field.boundsMax};
        bounds_.min = glm::min(bounds_.min, field.boundsMin);
        bounds_.max = glm::max(bounds_.max, field.boundsMax);
        any = true;
    }
    if (!any) bounds_ = {glm::vec3(INFINITY), glm::vec3(-INFINITY)}; // overlaps nothing
}

// --- Per plant ---------------------------------------------------------------------------------------------------

PlantTouch touchPlant(const Collider& c, glm::vec3 base, float height, const CategoryInteraction& response,
                      const RecoveryParams& recovery) {
    // The stem point nearest the collider's axis: exact for spheres and horizontal or vertical capsules (wheels,
    // downwash), a close approximation for tilted capsules and boxes.
    glm::vec3 axis = axisPoint(c, base + glm::vec3(0.0f, 0.0f, 0.5f * height));
    glm::vec3 q(base.x, base.y, std::clamp(axis.z, base.z, base.z + height));
    float sd = signedDistance(c, q);
    if (!(sd < 0.0f)) return {};
    float depth = -sd;
    axis = axisPoint(c, q);
    glm::vec2 away(q.x - axis.x, q.y - axis.y);
    float len2 = glm::dot(away, away);
    // A stem exactly on the axis has no "away": any fixed direction keeps the result deterministic.
    glm::vec2 dir = len2 > 1e-12f ? away / std::sqrt(len2) : glm::vec2(1.0f, 0.0f);

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

struct CollisionPass::Scratch {
    static constexpr uint32_t kNone = ~0u;
    std::vector<uint32_t> candidates;
    std::vector<uint32_t> slot;    // per plant of the cluster (index - range.x): its TouchSum, or kNone
    std::vector<uint32_t> touched; // plants of the cluster with a touch, in order of first touch
    std::vector<TouchSum> sums;    // parallel to touched
};

CollisionPass::CollisionPass(const VegetationTile& tile, const VegetationParams& vegetation,
                             const InteractionParams& params)
    : tile_(&tile), index_(tile, vegetation), params_(params), outputs_(tile.fields.size()) {}

void CollisionPass::collideField(uint32_t f, std::span<const Collider> colliders, Scratch& s, FieldOutput& out) const {
    constexpr uint32_t kSide = TileCollisionIndex::kCellsPerSide;
    const FieldVegetation& field = tile_->fields[f];
    if (field.plantCount() == 0) return;
    s.candidates.clear();
    bvh_.query({field.boundsMin, field.boundsMax}, s.candidates);
    if (s.candidates.empty()) return;
    out.tested = true;
    const TileCollisionIndex::Field& index = index_.field(f);
    const float cellSize = index_.cellSize(), invCell = 1.0f / cellSize;
    for (uint32_t k = 0; k < field.clusters.size(); ++k) {
        const gpu::PlantCluster& cluster = field.clusters[k];
        if (cluster.range.y == 0) continue;
        ++out.clustersTested;
        const Aabb clusterBox{glm::vec3(cluster.boundsMin), glm::vec3(cluster.boundsMax)};
        const glm::vec2 origin = field.origin + tile_->clusterSize * glm::vec2(float(k % tile_->clustersPerField),
                                                                               float(k / tile_->clustersPerField));
        if (s.slot.size() < cluster.range.y) s.slot.resize(cluster.range.y, Scratch::kNone);
        for (uint32_t rank : s.candidates) {
            const Aabb& b = bvh_.bounds(rank);
            if (!b.overlaps(clusterBox)) continue;
            const Collider& c = colliders[bvh_.inputIndex(rank)];
            // Stems are vertical, so only plants whose base lies in the collider's xy footprint can be touched.
            // Clamping keeps the cell range conservative for plants that a rounding put on the cluster's edge.
            auto cell = [&](float v, float o) {
                return uint32_t(std::clamp(int32_t(std::floor((v - o) * invCell)), 0, int32_t(kSide) - 1));
            };
            const uint32_t x0 = cell(b.min.x, origin.x), x1 = cell(b.max.x, origin.x);
            const uint32_t y0 = cell(b.min.y, origin.y), y1 = cell(b.max.y, origin.y);
            // Spheres (the common case: gusts, wheels seen from far, feet) are rejected with one squared distance
            // before the general hull test.
            const bool sphere = c.shape == ColliderShape::Sphere;
            const float r2 = c.radius * c.radius;
            for (uint32_t cy = y0; cy <= y1; ++cy) {
                const uint32_t row = k * kSide * kSide + cy * kSide;
                const uint32_t begin = index.cellStart[row + x0], end = index.cellStart[row + x1 + 1];
                out.plantsTested += end - begin;
                for (uint32_t i = begin; i < end; ++i) {
                    const TileCollisionIndex::Plant& p = index.plants[i];
                    if (p.x < b.min.x || p.x > b.max.x || p.y < b.min.y || p.y > b.max.y || p.z > b.max.z ||
                        p.z + p.height < b.min.z)
                        continue;
                    if (sphere) {
                        float dx = p.x - c.centre.x, dy = p.y - c.centre.y;
                        float dz = std::clamp(c.centre.z, p.z, p.z + p.height) - c.centre.z;
                        if (dx * dx + dy * dy + dz * dz >= r2) continue;
                    }
                    PlantTouch t =
                        touchPlant(c, {p.x, p.y, p.z}, p.height, params_.categories[p.category], params_.recovery);
                    if (t.kind == 0) continue;
                    // Candidates come in rank (= id) order, so each plant's sum is accumulated in id order.
                    uint32_t& slot = s.slot[p.plant - cluster.range.x];
                    if (slot == Scratch::kNone) {
                        slot = uint32_t(s.touched.size());
                        s.touched.push_back(p.plant);
                        s.sums.emplace_back();
                    }
                    s.sums[slot].add(t);
                }
            }
        }
        if (s.touched.empty()) continue;
        // Contacts leave sorted by plant; the slots are reset for the next cluster.
        std::sort(s.touched.begin(), s.touched.end());
        for (uint32_t plant : s.touched) {
            uint32_t& slot = s.slot[plant - cluster.range.x];
            gpu::PlantContact contact = s.sums[slot].contact(params_.recovery);
            contact.plant = field.firstPlant + plant;
            contact.field = f;
            out.contacts.push_back(contact);
            slot = Scratch::kNone;
        }
        s.touched.clear();
        s.sums.clear();
        out.clusters.push_back(field.firstCluster + k);
    }
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
        std::atomic<uint32_t> next{0};
        auto worker = [&] {
            Scratch scratch;
            for (uint32_t f; (f = next.fetch_add(1, std::memory_order_relaxed)) < fieldCount;)
                collideField(f, colliders, scratch, outputs_[f]);
        };
        std::vector<std::thread> pool;
        const uint32_t extra = std::min(threads, std::max(fieldCount, 1u)) - 1;
        for (uint32_t t = 0; t < extra; ++t) pool.emplace_back(worker);
        worker();
        for (std::thread& t : pool) t.join();
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
