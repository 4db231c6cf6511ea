#include "vegetation/vegetation_tile.h"

#include <algorithm>
#include <bit>

namespace sward {

VegetationStats countVegetation(const VegetationTile& tile) {
    VegetationStats stats;
    for (const FieldVegetation& f : tile.fields) {
        stats.plants += f.staticRecords.size();
        stats.staticBytes += f.staticRecords.size() * sizeof(gpu::PlantStatic);
        stats.dynamicBytes += f.dynamicRecords.size() * sizeof(gpu::PlantDynamic);
        stats.clusterBytes += f.clusters.size() * sizeof(gpu::PlantCluster);
    }
    return stats;
}

std::vector<gpu::PlantField> makeFieldTable(const VegetationTile& tile) {
    std::vector<gpu::PlantField> table;
    table.reserve(tile.fields.size());
    for (const FieldVegetation& f : tile.fields)
        table.push_back({.originStep = glm::vec4(f.origin, f.positionStep, 0.0f),
                         .range = glm::uvec4(f.firstPlant, f.plantCount(), f.firstCluster, f.clusters.size())});
    return table;
}

std::vector<ClusterBox> clusterBoxes(const VegetationTile& tile) {
    std::vector<ClusterBox> boxes;
    for (const FieldVegetation& f : tile.fields)
        for (const gpu::PlantCluster& c : f.clusters) boxes.push_back({glm::vec3(c.boundsMin), glm::vec3(c.boundsMax)});
    return boxes;
}

void frontToBack(std::span<const ClusterBox> boxes, glm::vec3 eye, std::vector<uint32_t>& order) {
    // Non-negative floats order as their bits do: one 64-bit key per cluster, distance above index.
    std::vector<uint64_t> keys(boxes.size());
    for (uint32_t i = 0; i < uint32_t(boxes.size()); ++i) {
        const glm::vec3 outside = glm::max(glm::max(boxes[i].min - eye, eye - boxes[i].max), glm::vec3(0.0f));
        keys[i] = uint64_t(std::bit_cast<uint32_t>(glm::dot(outside, outside))) << 32 | i;
    }
    std::sort(keys.begin(), keys.end());
    order.resize(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) order[i] = uint32_t(keys[i]);
}

} // namespace sward
