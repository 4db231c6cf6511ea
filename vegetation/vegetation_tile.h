// The vegetation data structure of paper section 3.2: scene tile (500 x 500 m) -> grass fields (25 x 25 m) ->
// plant clusters (5 x 5 m). A field is the unit the renderer uploads, culls and simulates; its plants live in a
// static record array (written once) and a dynamic record array (interaction state), both ordered by cluster.
// Every array is a plain std::vector of the structs in shaders/shared/plant_layout.h, so an upload is one memcpy.
#pragma once

#include "shared/plant_layout.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

// Index of a scene tile; tile (x, y) covers worldOrigin + tileSize * [x, x+1) x [y, y+1).
struct TileCoord {
    int32_t x = 0, y = 0;
    bool operator==(const TileCoord&) const = default;
};

// Index of a grass field inside its tile, 0 .. fieldsPerTile-1 on each axis (x east, y north).
struct FieldCoord {
    uint32_t x = 0, y = 0;
    bool operator==(const FieldCoord&) const = default;
};

// Byte range inside one of the tile's GPU buffers.
struct BufferRange {
    uint64_t offset = 0, size = 0;
};

struct FieldVegetation {
    FieldCoord coord;
    glm::vec2 origin{0.0f};    // world xy of the field's min corner: the decoding origin of its positions
    float positionStep = 0.0f; // metres per position step (fieldSize / kPlantPositionSteps)
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f}; // union of its non-empty clusters' boxes (min = max when empty)

    std::vector<gpu::PlantStatic> staticRecords;   // ordered by cluster, then category
    std::vector<gpu::PlantDynamic> dynamicRecords; // parallel to staticRecords, initially at rest
    std::vector<gpu::PlantCluster> clusters;       // clustersPerField^2, row-major (x fastest)

    // Where the field sits in its tile's buffers if all fields are packed in field order (set by generateTile;
    // zero for a field generated alone). firstPlant / firstCluster are element indices, the ranges bytes.
    uint32_t firstPlant = 0, firstCluster = 0;
    BufferRange staticRange, dynamicRange;

    // Interaction bookkeeping, owned by the simulation: a field is active while colliders touch it and
    // timeStamp is the simulation step of its last update.
    bool active = false;
    uint64_t timeStamp = 0;

    uint32_t plantCount() const { return uint32_t(staticRecords.size()); }
};

struct VegetationTile {
    TileCoord coord;
    glm::vec2 origin{0.0f}; // world xy of the tile's min corner
    float size = 0.0f, fieldSize = 0.0f, clusterSize = 0.0f;
    uint32_t fieldsPerSide = 0, clustersPerField = 0;
    std::vector<FieldVegetation> fields; // fieldsPerSide^2, row-major (x fastest)

    const FieldVegetation& field(FieldCoord c) const { return fields[size_t(c.y) * fieldsPerSide + c.x]; }
};

struct VegetationStats {
    uint64_t plants = 0;
    uint64_t staticBytes = 0, dynamicBytes = 0, clusterBytes = 0;
    uint64_t totalBytes() const { return staticBytes + dynamicBytes + clusterBytes; }
};

// Plant count and GPU record bytes of a tile.
VegetationStats countVegetation(const VegetationTile& tile);

// The per-field GPU table (decoding origin, record and cluster ranges), in field order.
std::vector<gpu::PlantField> makeFieldTable(const VegetationTile& tile);

// A cluster's box (gpu::PlantCluster's bounds), by tile cluster index: field index * clustersPerField^2 + the
// cluster's index in its field, the expansion's numbering.
struct ClusterBox {
    glm::vec3 min{0.0f}, max{0.0f};
};
std::vector<ClusterBox> clusterBoxes(const VegetationTile& tile);

// The tile's cluster indices front to back from `eye`: by the squared distance from the eye to the cluster's box
// (0 inside it), ties by index, so the order is a pure function of the boxes and the eye. The expansion lays each
// LOD's instances out in this order, so nearer plants are drawn first and the depth test rejects what they hide
// before it is shaded.
void frontToBack(std::span<const ClusterBox> boxes, glm::vec3 eye, std::vector<uint32_t>& order);

} // namespace sward
