#include "vegetation/vegetation_tile.h"

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

} // namespace sward
