// Memory: a few large VkDeviceMemory blocks, sub-allocated by intent.
//
// Vulkan implementations limit the number of live allocations (maxMemoryAllocationCount may be 4096) and
// vkAllocateMemory is slow, so buffers and images never get their own allocation: they take ranges of
// 64 MiB blocks. Callers say what the memory is for (MemoryIntent), not which property flags it needs.
#pragma once

#include "engine/vk_common.h"

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace sward {

class Device;

// First-fit range allocator over [0, capacity) with coalescing frees. Vulkan-free, unit-tested alone.
class RangeAllocator {
public:
    explicit RangeAllocator(uint64_t capacity);
    // Offset of a free range of `size` bytes aligned to `alignment` (a power of two), or nullopt if none.
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
    // Returns a range previously handed out by allocate (same offset and size).
    void free(uint64_t offset, uint64_t size);
    uint64_t capacity() const { return capacity_; }
    uint64_t used() const { return used_; }
    size_t freeRangeCount() const { return free_.size(); }

private:
    uint64_t capacity_, used_ = 0;
    std::map<uint64_t, uint64_t> free_; // offset -> size, never adjacent (always coalesced)
};

enum class MemoryIntent {
    DeviceLocal, // GPU-only data: plant records, render targets, vertex output
    Upload,      // written by the CPU, read by the GPU: staging, per-frame constants
    Readback,    // written by the GPU, read by the CPU: images and results copied back
};

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint64_t offset = 0;
    uint64_t size = 0;
    uint8_t* mapped = nullptr; // persistently mapped pointer for host-visible intents, else null
    uint32_t block = ~0u;
};

struct MemoryStats {
    uint32_t blocks = 0;           // live vkAllocateMemory allocations
    uint64_t reservedBytes = 0;    // sum of block sizes
    uint64_t usedBytes = 0;        // sum of live sub-allocations
    uint32_t liveAllocations = 0;  // live sub-allocations
};

class Allocator {
public:
    static constexpr uint64_t kBlockSize = 64ull << 20;

    explicit Allocator(Device& device);
    ~Allocator();
    Allocator(const Allocator&) = delete;
    Allocator& operator=(const Allocator&) = delete;

    // `linear` separates buffers from optimally tiled images so bufferImageGranularity never matters.
    Allocation allocate(const VkMemoryRequirements& requirements, MemoryIntent intent, bool linear);
    void free(const Allocation& allocation);
    MemoryStats stats() const;

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t memoryType = 0;
        bool linear = true;
        uint8_t* mapped = nullptr;
        std::unique_ptr<RangeAllocator> ranges;
    };
    uint32_t chooseMemoryType(uint32_t typeBits, MemoryIntent intent) const;

    Device& device_;
    std::vector<Block> blocks_; // freed blocks keep their slot (memory == null) so indices stay valid
    uint32_t liveAllocations_ = 0;
};

} // namespace sward
