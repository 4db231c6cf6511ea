// The colliders of one tick in a bounding volume hierarchy, so the collision pass meets each field's box with only
// the colliders near it.
#pragma once

#include "interaction/colliders.h"

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

// Colliders in a linear bounding volume hierarchy (Morton order), rebuilt per tick. Ranks are positions in
// (id, input index) order.
class ColliderBvh {
public:
    // Keeps the colliders whose bounds overlap `keep` (the vegetation's bounds) and builds the tree over them.
    void build(std::span<const Collider> colliders, const Aabb& keep);
    // Appends the ranks of the kept colliders whose bounds overlap box, in ascending rank (= id) order.
    void query(const Aabb& box, std::vector<uint32_t>& ranks) const;

    uint32_t size() const { return uint32_t(input_.size()); }
    uint32_t inputIndex(uint32_t rank) const { return input_[rank]; } // index into build()'s span
    const Aabb& bounds(uint32_t rank) const { return bounds_[rank]; }

private:
    void sortAlongMortonCurve();
    void buildLevels();

    struct Node {
        Aabb box;
        uint32_t first = 0, count = 0; // leaf: items_[first, first + count); inner (count 0): children first, first+1
    };
    struct Kept {
        uint32_t id, input;
        Aabb box;
    };
    std::vector<Kept> kept_;                // scratch of build(), kept for its capacity
    std::vector<uint64_t> keys_, keysTmp_;  // likewise
    std::vector<uint32_t> input_; // rank -> input index
    std::vector<Aabb> bounds_;    // by rank
    std::vector<uint32_t> items_; // ranks in tree order
    std::vector<Node> nodes_;
    uint32_t root_ = 0;
};

} // namespace sward
