// The colliders of one tick binned into the tile's grid of fields, so the collision pass meets each field with only
// the colliders whose boxes overlap the field's.
#pragma once

#include "interaction/colliders.h"

#include "common/parallel_for.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace sward {

struct VegetationTile;

// The cell of a regular grid of `count` cells of 1 / inverseSize metres from origin that holds v, clamped to the grid
// (so NaN and values far beyond it cannot overflow the conversion). floor without libm: truncation is floor for the
// positive values it is applied to.
inline uint32_t gridCell(float v, float origin, float inverseSize, uint32_t count) {
    const float c = (v - origin) * inverseSize;
    return c > 0.0f ? (c < float(count) ? uint32_t(c) : count - 1) : 0u;
}

// Per field, the ranks of the colliders overlapping its box. Fields tile a regular grid, so each collider's box
// names the few fields it can meet by arithmetic: binning is O(colliders + pairs) with no tree to build or walk
// (the linear BVH it replaced cost 0.2 ms to build over 10,000 colliders and 4,500 instructions a field query,
// docs/benchmarks.md). Ranks are positions in (id, input index) order, and each field's list is ascending, so
// results never depend on the input's order beyond ids.
//
// Built in two steps so that the binning can run on several threads: begin() keeps and ranks the colliders (on the
// calling thread), then binShare() bins each of `shares` contiguous ranges of ranks into lists of its own. A field's
// ranks are its lists of share 0, 1, ... one after the other: ascending, and the same for any number of shares.
class ColliderGrid {
public:
    // tile must outlive the grid: its grid of fields is read at every begin (the fields' boxes are copied here).
    explicit ColliderGrid(const VegetationTile& tile);

    // Keeps the colliders whose bounds overlap `keep` (the vegetation's bounds), ranks them and splits the ranks into
    // `shares` (>= 1) ranges, to be binned by binShare(0 .. shares - 1) before ranks() is called.
    void begin(std::span<const Collider> colliders, const Aabb& keep, uint32_t shares);
    // Bins the ranks of one share into the fields. Shares may be binned at once on different threads.
    void binShare(uint32_t share);

    uint32_t shares() const { return uint32_t(shares_.size()); }
    // The ranks of share `share` whose bounds overlap field f's box, ascending (empty for an empty field). Every rank
    // of a share is below every rank of the next.
    std::span<const uint32_t> ranks(uint32_t field, uint32_t share) const {
        const Share& s = shares_[share];
        return {s.fieldRanks.data() + s.fieldStart[field], s.fieldStart[field + 1] - s.fieldStart[field]};
    }

    uint32_t size() const { return uint32_t(input_.size()); }
    uint32_t inputIndex(uint32_t rank) const { return input_[rank]; } // index into begin()'s span
    const Aabb& bounds(uint32_t rank) const { return bounds_[rank]; }

private:
    // Calls visit(field) for every field whose box overlaps box.
    template <class Visit> void forEachField(const Aabb& box, Visit&& visit) const;

    struct Kept {
        uint32_t id, input;
        Aabb box;
    };
    // A range of ranks and its lists, written by the thread binning it: aligned apart from the next share's.
    struct alignas(kWorkerScratchAlignment) Share {
        uint32_t begin = 0, end = 0;                      // ranks
        std::vector<std::pair<uint32_t, uint32_t>> pairs; // scratch of binShare(): (field, rank), ranks ascending
        std::vector<uint32_t> fieldStart;                 // fields + 1 offsets into fieldRanks
        std::vector<uint32_t> fieldRanks;                 // by field, then rank
    };
    const VegetationTile* tile_ = nullptr;
    std::vector<Aabb> fieldBoxes_; // by field; empty fields hold an inverted box that overlaps nothing
    float margin_ = 0.0f;          // how far any field's box reaches beyond its grid square, metres (+ rounding)
    std::vector<Kept> kept_;       // scratch of begin(), kept for its capacity
    std::vector<uint32_t> input_;  // rank -> input index
    std::vector<Aabb> bounds_;     // by rank
    std::vector<Share> shares_;    // kept for their capacity; resized by begin()
};

} // namespace sward
