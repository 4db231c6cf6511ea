// VegetationBuffers: one tile's plant records on the GPU (paper section 3.2).
//
// All fields are packed in field order into four device-local buffers, sub-allocated like every other buffer:
//   statics   PlantStatic[plants]   written once at load, never touched again
//   dynamics  PlantDynamic[plants]  interaction state; only touched clusters' byte ranges are ever rewritten
//   clusters  PlantCluster[clusters] culling boxes and plant ranges (relative to their field)
//   fields    PlantField[fields]     decoding origin/step and plant / cluster ranges
// The CPU copy may be discarded after construction.
#pragma once

#include "engine/context.h"
#include "engine/resources.h"
#include "vegetation/vegetation_tile.h"

namespace sward {

class VegetationBuffers {
public:
    // Uploads through one staging buffer and waits. Requires a non-empty tile (fields generated).
    VegetationBuffers(Context& ctx, const VegetationTile& tile);
    ~VegetationBuffers();
    VegetationBuffers(const VegetationBuffers&) = delete;
    VegetationBuffers& operator=(const VegetationBuffers&) = delete;

    Buffer statics, dynamics, clusters, fields;
    uint32_t plantCount = 0, clusterCount = 0, fieldCount = 0;
    uint32_t clustersPerField = 0; // per field (not per side): cluster i belongs to field i / clustersPerField
    double uploadSeconds = 0.0;    // wall time of staging + copy + wait

private:
    Context& ctx_;
};

} // namespace sward
