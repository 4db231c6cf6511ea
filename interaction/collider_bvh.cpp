#include "interaction/collider_bvh.h"

#include <algorithm>

namespace sward {

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
    sortAlongMortonCurve();
    buildLevels();
}

// items_ = the ranks in Morton order of their box centres, ties by rank.
void ColliderBvh::sortAlongMortonCurve() {
    const uint32_t n = uint32_t(bounds_.size());
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
}

// nodes_ = the leaves over items_, then each level above them; root_ = the last level's only node.
void ColliderBvh::buildLevels() {
    const uint32_t n = uint32_t(items_.size());
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

} // namespace sward
