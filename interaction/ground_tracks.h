// Ground tracks: the ruts wheels (and any push collider with RutParams) press into the ground (paper section 4:
// tyre tracks on vegetated and non-vegetated surfaces; issue 18).
//
// Ruts live on a world-wide lattice of gpu::kTrackCell metres (shaders/shared/gpu_layout.h), allocated in blocks of
// kTrackBlockCells^2 vertices the first time a rut reaches them, so untouched ground costs nothing. A collider
// resting on the ground presses a vertex down by its rut depth minus the gap between its hull and the ground there
// (a wheel resting on the ground leaves a rut of rut_depth, shaped by its hull); a tread raises the rut's floor by
// tread_depth in grooves across the direction of travel. A vertex keeps the deepest rut ever pressed into it (the
// maximum: the same whatever order colliders come in), so tracks are a pure function of the colliders of every
// tick: shards, resumed runs and restored states reproduce them bitwise.
#pragma once

#include "interaction/colliders.h"

#include <compare>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace sward {

class Ground;

struct TrackBlockKey {
    int32_t x = 0, y = 0; // block (x, y) owns lattice vertices [x, x + 1) * kTrackBlockCells in i (j alike)
    // Row by row: the order of the state file and of the GPU upload.
    std::strong_ordering operator<=>(const TrackBlockKey& o) const { return y != o.y ? y <=> o.y : x <=> o.x; }
    bool operator==(const TrackBlockKey&) const = default;
};

// A block's own vertices' rut depths, metres, row after row (kTrackBlockCells^2 values).
using TrackBlock = std::vector<float>;
using TrackBlocks = std::map<TrackBlockKey, TrackBlock>;

// The world position of lattice vertex (i, j), metres: the one conversion (CPU stamping and drawn patches alike).
glm::vec2 trackVertexPosition(int64_t i, int64_t j);
// The block owning lattice index i (floor division by kTrackBlockCells).
int32_t trackBlockOf(int64_t i);

class GroundTracks {
public:
    // Presses the ruts of the colliders of `current` with rut.depth > 0 into `ground`. One also in `previous` (the
    // same id at the previous tick) is swept from that pose to this one in steps of at most half a lattice cell,
    // so a fast wheel leaves a continuous rut instead of a row of prints; moves over kMaxSweep metres are jumps.
    void press(std::span<const Collider> previous, std::span<const Collider> current, const Ground& ground);

    // Rut depth at lattice vertex (i, j), metres; 0 where nothing was pressed.
    float depth(int64_t i, int64_t j) const;
    const TrackBlocks& blocks() const { return blocks_; }

    // Change counters for whoever draws the ruts: revision() grows with every press that changed a depth, and a
    // block's revision is the value revision() took when its drawn patch (own vertices, shared edge, ring and the
    // vertices its normals look at) last changed. A restore() replaces every block and changes generation().
    uint64_t revision() const { return revision_; }
    uint64_t blockRevision(TrackBlockKey key) const;
    uint64_t generation() const { return generation_; }
    // Replaces every block (a restored state). Requires each block to hold kTrackBlockCells^2 finite depths >= 0.
    void restore(TrackBlocks blocks);

    static constexpr float kMaxSweep = 2.0f;

private:
    void pressVertex(int64_t i, int64_t j, float depth);
    void pressHull(const Collider& hull, glm::vec2 forward, const Ground& ground);

    TrackBlocks blocks_;
    std::map<TrackBlockKey, uint64_t> revisions_;
    uint64_t revision_ = 0, generation_ = 0;
    bool changed_ = false; // within one press()
};

} // namespace sward
