#include "render/vegetation_buffers.h"

#include "common/stopwatch.h"

#include "engine/barriers.h"

#include <algorithm>
#include <cstring>

namespace sward {

VegetationBuffers::VegetationBuffers(Context& ctx, const VegetationTile& tile) : ctx_(ctx) {
    const Stopwatch upload;
    require(!tile.fields.empty(), "cannot upload a tile without fields");
    VegetationStats stats = countVegetation(tile);
    std::vector<gpu::PlantField> table = makeFieldTable(tile);
    plantCount = uint32_t(stats.plants);
    fieldCount = uint32_t(tile.fields.size());
    clustersPerField = tile.clustersPerField * tile.clustersPerField;
    clusterCount = fieldCount * clustersPerField;

    // Zero-plant tiles still get valid (minimum-size) buffers so descriptors never point at nothing.
    auto sized = [](uint64_t bytes) { return std::max<uint64_t>(bytes, 16); };
    // Each is bound whole as one storage buffer: within maxStorageBufferRange (128 MiB guaranteed = the 16-byte
    // records of 8 Mi plants; lavapipe reports exactly that, GPUs 1-4 GiB), or one error instead of a bad binding.
    const uint64_t range = ctx.device.properties().limits.maxStorageBufferRange,
                   largest = std::max({stats.staticBytes, stats.dynamicBytes, stats.clusterBytes});
    require(largest <= range, "a vegetation tile of " + std::to_string(stats.plants) + " plants needs " +
                                  std::to_string(largest >> 20) + " MiB of plant records in one buffer; the GPU '" +
                                  ctx.device.name() + "' binds at most " + std::to_string(range >> 20) +
                                  " MiB (maxStorageBufferRange)");
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    statics = createBuffer(ctx, sized(stats.staticBytes), usage, MemoryIntent::DeviceLocal);
    dynamics = createBuffer(ctx, sized(stats.dynamicBytes), usage, MemoryIntent::DeviceLocal);
    clusters = createBuffer(ctx, sized(stats.clusterBytes), usage, MemoryIntent::DeviceLocal);
    fields = createBuffer(ctx, sized(table.size() * sizeof(gpu::PlantField)), usage, MemoryIntent::DeviceLocal);

    // One staging buffer, four copies, one submission: the fields are already packed in field order.
    const uint64_t total = stats.staticBytes + stats.dynamicBytes + stats.clusterBytes + table.size() * sizeof(gpu::PlantField);
    Buffer staging = createBuffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryIntent::Upload);
    uint8_t* out = staging.mapped();
    uint64_t staticAt = 0, dynamicAt = stats.staticBytes, clusterAt = dynamicAt + stats.dynamicBytes,
             fieldAt = clusterAt + stats.clusterBytes;
    uint64_t s = staticAt, d = dynamicAt, c = clusterAt;
    // An empty field's vectors have a null data(): memcpy from null is undefined even for zero bytes.
    auto copy = [&](uint64_t at, const void* from, size_t bytes) {
        if (bytes > 0) std::memcpy(out + at, from, bytes);
    };
    for (const FieldVegetation& field : tile.fields) {
        copy(s, field.staticRecords.data(), field.staticRecords.size() * sizeof(gpu::PlantStatic));
        copy(d, field.dynamicRecords.data(), field.dynamicRecords.size() * sizeof(gpu::PlantDynamic));
        copy(c, field.clusters.data(), field.clusters.size() * sizeof(gpu::PlantCluster));
        s += field.staticRecords.size() * sizeof(gpu::PlantStatic);
        d += field.dynamicRecords.size() * sizeof(gpu::PlantDynamic);
        c += field.clusters.size() * sizeof(gpu::PlantCluster);
    }
    copy(fieldAt, table.data(), table.size() * sizeof(gpu::PlantField));

    ctx.submitter.immediate([&](VkCommandBuffer cmd) {
        auto copy = [&](const Buffer& dst, uint64_t from, uint64_t size) {
            if (size == 0) return;
            VkBufferCopy region{.srcOffset = from, .dstOffset = 0, .size = size};
            vkCmdCopyBuffer(cmd, staging.handle, dst.handle, 1, &region);
        };
        copy(statics, staticAt, stats.staticBytes);
        copy(dynamics, dynamicAt, stats.dynamicBytes);
        copy(clusters, clusterAt, stats.clusterBytes);
        copy(fields, fieldAt, table.size() * sizeof(gpu::PlantField));
        // The records are read by compute (expansion, recovery) in later submissions.
        copyToComputeReadBarrier(cmd);
    });
    destroyBuffer(ctx, staging);
    uploadSeconds = upload.seconds();
}

VegetationBuffers::~VegetationBuffers() {
    retireBuffer(ctx_, statics);
    retireBuffer(ctx_, dynamics);
    retireBuffer(ctx_, clusters);
    retireBuffer(ctx_, fields);
}

} // namespace sward
