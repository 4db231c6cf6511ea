#include "interaction/collider_grid.h"

#include "vegetation/vegetation_tile.h"

#include <algorithm>
#include <cassert>

namespace sward {

ColliderGrid::ColliderGrid(const VegetationTile& tile) : tile_(&tile), fieldBoxes_(tile.fields.size()) {
    for (uint32_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        if (field.plantCount() == 0) {
            fieldBoxes_[f] = {glm::vec3(INFINITY), glm::vec3(-INFINITY)};
            continue;
        }
        fieldBoxes_[f] = {field.boundsMin, field.boundsMax};
        const glm::vec2 square =
            tile.origin + tile.fieldSize * glm::vec2(float(f % tile.fieldsPerSide), float(f / tile.fieldsPerSide));
        const glm::vec2 below = square - glm::vec2(field.boundsMin);
        const glm::vec2 above = glm::vec2(field.boundsMax) - (square + tile.fieldSize);
        margin_ = std::max({margin_, below.x, below.y, above.x, above.y});
    }
    // The grid arithmetic below rounds: a millimetre more keeps the range of fields visited conservative, and the
    // exact box test decides.
    margin_ += 1e-3f;
}

template <class Visit> void ColliderGrid::forEachField(const Aabb& box, Visit&& visit) const {
    const uint32_t n = tile_->fieldsPerSide;
    const float inverse = 1.0f / tile_->fieldSize;
    const glm::vec2 o = tile_->origin;
    const uint32_t x0 = gridCell(box.min.x - margin_, o.x, inverse, n),
                   x1 = gridCell(box.max.x + margin_, o.x, inverse, n);
    const uint32_t y0 = gridCell(box.min.y - margin_, o.y, inverse, n),
                   y1 = gridCell(box.max.y + margin_, o.y, inverse, n);
    for (uint32_t y = y0; y <= y1; ++y)
        for (uint32_t x = x0; x <= x1; ++x) {
            const uint32_t f = y * n + x;
            if (fieldBoxes_[f].overlaps(box)) visit(f);
        }
}

void ColliderGrid::begin(std::span<const Collider> colliders, const Aabb& keep, uint32_t shares) {
    assert(shares >= 1);
    // Colliders far from any plant (high above, off the tile) are dropped first: they are the bulk of a large scene
    // and must cost one box test each. Callers usually list colliders in id order already: then the kept ones are
    // the ranks as they come, and sorting is skipped.
    input_.clear();
    bounds_.clear();
    bool sorted = true;
    for (uint32_t i = 0; i < colliders.size(); ++i) {
        const Aabb b = worldBounds(colliders[i]);
        if (!b.overlaps(keep)) continue;
        sorted = sorted && (input_.empty() || colliders[input_.back()].id <= colliders[i].id);
        input_.push_back(i);
        bounds_.push_back(b);
    }
    const uint32_t n = uint32_t(input_.size());
    if (!sorted) {
        std::vector<Kept>& kept = kept_;
        kept.resize(n);
        for (uint32_t r = 0; r < n; ++r) kept[r] = {colliders[input_[r]].id, input_[r], bounds_[r]};
        std::sort(kept.begin(), kept.end(),
                  [](const Kept& a, const Kept& b) { return a.id != b.id ? a.id < b.id : a.input < b.input; });
        for (uint32_t r = 0; r < n; ++r) {
            input_[r] = kept[r].input;
            bounds_[r] = kept[r].box;
        }
    }
    shares_.resize(shares);
    for (uint32_t k = 0; k < shares; ++k) {
        shares_[k].begin = uint32_t(uint64_t(n) * k / shares);
        shares_[k].end = uint32_t(uint64_t(n) * (k + 1) / shares);
    }
}

void ColliderGrid::binShare(uint32_t share) {
    // A counting sort of the (field, rank) pairs, made in ascending rank order and stable: each field's list comes
    // out ascending, whatever the input order.
    Share& s = shares_[share];
    s.pairs.clear();
    s.fieldStart.assign(fieldBoxes_.size() + 1, 0u);
    for (uint32_t r = s.begin; r < s.end; ++r)
        forEachField(bounds_[r], [&](uint32_t f) {
            s.pairs.emplace_back(f, r);
            ++s.fieldStart[f + 1];
        });
    for (size_t f = 1; f < s.fieldStart.size(); ++f) s.fieldStart[f] += s.fieldStart[f - 1];
    s.fieldRanks.resize(s.pairs.size());
    for (auto [f, r] : s.pairs) s.fieldRanks[s.fieldStart[f]++] = r;
    // The fill moved each start to the next field's: shift back.
    for (size_t f = s.fieldStart.size() - 1; f > 0; --f) s.fieldStart[f] = s.fieldStart[f - 1];
    s.fieldStart[0] = 0;
}

} // namespace sward
