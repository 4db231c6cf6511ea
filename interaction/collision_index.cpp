#include "interaction/collision_index.h"

#include "interaction/collider_grid.h"
#include "vegetation/records.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <span>
#include <string>

#include <sys/mman.h>

namespace sward {

void TileCollisionIndex::Free::operator()(void* p) const { std::free(p); }

TileCollisionIndex::TileCollisionIndex(const VegetationTile& tile, const VegetationParams& params) {
    constexpr uint32_t kCells = kCellsX * kCellsY;
    cellSize_ = tile.clusterSize / glm::vec2(float(kCellsX), float(kCellsY));
    const glm::vec2 inverseCell = 1.0f / cellSize_;
    for (uint32_t category = 0; category < 4; ++category)
        for (uint32_t size = 0; size < 256; ++size)
            heights_[category | size << 2] = params.categories[category].height * float(size) / gpu::kPlantSizeDivisor;
    size_t total = 0, totalCells = 0;
    for (const FieldVegetation& field : tile.fields) {
        require(field.plantCount() <= kMaxFieldPlants,
                "a field holds " + std::to_string(field.plantCount()) +
                    " plants; the collision pass supports at most " + std::to_string(kMaxFieldPlants) +
                    " per field (use smaller fields)");
        total += field.plantCount();
        totalCells += field.clusters.size() * kCells + 1;
    }
    // One block for every stem and then every cell offset, 2 MiB aligned so the kernel can back it with
    // transparent huge pages: a tick touches a few lines in each of hundreds of fields, and a TLB miss per field
    // (4 KiB pages, nested paging in a VM) costs as much as the lines themselves.
    constexpr size_t kHuge = size_t(2) << 20;
    const size_t used = (total + kPaddingStems) * sizeof(Stem) + totalCells * sizeof(uint32_t);
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
    std::fill_n(stems_.get() + total, kPaddingStems, Stem{});
    uint32_t* cells = reinterpret_cast<uint32_t*>(stems_.get() + total + kPaddingStems);
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
                // The pass finds a collider's sub-cells with the same gridCell: monotonic in the coordinate, so a
                // plant inside the collider's box is never in a sub-cell before the box's first.
                cellOf[i] = k * kCells + gridCell(p.y, origin.y, inverseCell.y, kCellsY) * kCellsX +
                            gridCell(p.x, origin.x, inverseCell.x, kCellsX);
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

} // namespace sward
