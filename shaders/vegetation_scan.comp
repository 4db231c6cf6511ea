#version 460
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum of the per-cluster LOD counts, in the frame's cluster order (front to back from the camera:
// vegetation_tile.h, frontToBack), by a single workgroup; turns counts into instance offsets (in place) and writes
// the indexed indirect draw commands, one per LOD and one for the near blades (the plant index buffers hold each
// LOD's pattern: plantFirstIndex, then the blades' pattern). A
// tile's instances are laid out as [all near | all mid | all far], each LOD in that cluster order, from the pool's
// cursor on; the scan advances the cursor past what it kept, so the tiles of a frame (expanded one after another, in
// tile order) share one pool.
#include "shared/config.h"
#include "shared/gpu_layout.h"
#include "shared/plant_blades.h"

layout(local_size_x = kScanGroupSize) in;

struct DrawIndexedIndirectCommand { // VkDrawIndexedIndirectCommand
    uint indexCount;
    uint instanceCount;
    uint firstIndex;
    int vertexOffset;
    uint firstInstance;
};

layout(set = 0, binding = kScanBindingClusterCounts, std430) buffer ClusterCounts { uvec4 clusterCounts[]; };
layout(set = 0, binding = kScanBindingDraws, std430) writeonly buffer Draws { DrawIndexedIndirectCommand draws[]; };
layout(set = 0, binding = kScanBindingStats, std430) writeonly buffer Stats { ExpansionStats stats; };
layout(set = 0, binding = kScanBindingCursor, std430) buffer Cursor { uint cursor; };
layout(set = 0, binding = kScanBindingClusterOrder, std430) readonly buffer Order { uint clusterOrder[]; };
layout(push_constant) uniform Push { ScanConstants push; };

shared uvec4 partial[kScanGroupSize];
shared uint visibleClusters;

void main() {
    uint lane = gl_LocalInvocationID.x;
    uint perLane = (push.clusterCount + kScanGroupSize - 1u) / kScanGroupSize;
    uint begin = min(lane * perLane, push.clusterCount), end = min(begin + perLane, push.clusterCount);
    if (lane == 0u) visibleClusters = 0u;
    barrier();
    uvec4 sum = uvec4(0u);
    uint visible = 0u;
    for (uint i = begin; i < end; ++i) {
        uvec4 counts = clusterCounts[clusterOrder[i]]; // w: plants of the cluster if it was visible, else 0
        sum += counts;
        visible += counts.w > 0u ? 1u : 0u;
    }
    atomicAdd(visibleClusters, visible); // a sum: order-independent
    partial[lane] = sum;
    barrier();
    for (uint offset = 1u; offset < kScanGroupSize; offset <<= 1u) {
        uvec4 add = lane >= offset ? partial[lane - offset] : uvec4(0u);
        barrier();
        partial[lane] += add;
        barrier();
    }
    uvec4 total = partial[kScanGroupSize - 1u];
    uint first = push.firstTile != 0u ? 0u : cursor; // every lane reads it before lane 0 advances it (barrier)
    uvec4 lodBase = uvec4(first, first + total.x, first + total.x + total.y, 0u);
    uvec4 running = partial[lane] - sum; // exclusive prefix of this lane's chunk
    for (uint i = begin; i < end; ++i) {
        uint cluster = clusterOrder[i];
        uvec4 counts = clusterCounts[cluster];
        clusterCounts[cluster] = uvec4(lodBase.xyz + running.xyz, 0u);
        running += counts;
    }
    if (lane < kLodCount) {
        uint base = lodBase[lane];
        uint count = total[lane];
        uint kept = base >= push.capacity ? 0u : min(count, push.capacity - base);
        draws[lane] = DrawIndexedIndirectCommand(plantVertexCount(lane, push.cutoutCorners), kept,
                                                 plantFirstIndex(lane, push.cutoutCorners), 0, base);
        // The near blades (plant_blades.h): the same near instances, the blade pattern after the LODs' patterns.
        if (lane == kLodNear)
            draws[kLodCount] = DrawIndexedIndirectCommand(push.nearBlades * kBladeIndices,
                                                          push.nearBlades > 0u ? kept : 0u,
                                                          plantFirstIndex(kLodCount, push.cutoutCorners), 0, base);
    }
    barrier();
    if (lane == 0u) {
        uint all = total.x + total.y + total.z;
        uint room = push.capacity - min(first, push.capacity);
        stats.instances = uvec4(total.xyz, all);
        stats.info = uvec4(visibleClusters, all > room ? all - room : 0u, total.w, first);
        cursor = first + min(all, room);
    }
}
