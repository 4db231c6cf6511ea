#include "engine/memory.h"

#include "engine/device.h"

#include <bit>

namespace sward {

RangeAllocator::RangeAllocator(uint64_t capacity) : capacity_(capacity) {
    if (capacity > 0) free_[0] = capacity;
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
    require(size > 0 && std::has_single_bit(alignment), "range allocation needs a size and a power-of-two alignment");
    for (auto it = free_.begin(); it != free_.end(); ++it) {
        uint64_t start = it->first, end = it->first + it->second;
        uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
        if (aligned + size > end) continue;
        free_.erase(it);
        if (aligned > start) free_[start] = aligned - start; // keep the alignment gap
        if (aligned + size < end) free_[aligned + size] = end - (aligned + size);
        used_ += size;
        return aligned;
    }
    return std::nullopt;
}

void RangeAllocator::free(uint64_t offset, uint64_t size) {
    auto next = free_.lower_bound(offset);
    require(offset + size <= capacity_ && (next == free_.end() || offset + size <= next->first),
            "range freed twice or never allocated");
    used_ -= size;
    if (next != free_.end() && next->first == offset + size) { // merge with the following free range
        size += next->second;
        next = free_.erase(next);
    }
    if (next != free_.begin()) { // merge with the preceding free range
        auto prev = std::prev(next);
        require(prev->first + prev->second <= offset, "range freed twice or never allocated");
        if (prev->first + prev->second == offset) {
            prev->second += size;
            return;
        }
    }
    free_[offset] = size;
}

Allocator::Allocator(Device& device) : device_(device) {}

Allocator::~Allocator() {
    for (Block& block : blocks_)
        if (block.memory) vkFreeMemory(device_.handle(), block.memory, nullptr);
}

uint32_t Allocator::chooseMemoryType(uint32_t typeBits, MemoryIntent intent) const {
    VkMemoryPropertyFlags required = 0, preferred = 0, avoided = 0;
    switch (intent) {
    case MemoryIntent::DeviceLocal:
        required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        avoided = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT; // keep small host-visible heaps (BAR) for uploads
        break;
    case MemoryIntent::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        avoided = VK_MEMORY_PROPERTY_HOST_CACHED_BIT; // write-combined is fastest for sequential CPU writes
        break;
    case MemoryIntent::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT; // CPU reads from uncached memory are very slow
        break;
    }
    const VkPhysicalDeviceMemoryProperties& props = device_.memoryProperties();
    int best = -1, bestScore = -1;
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
        VkMemoryPropertyFlags flags = props.memoryTypes[i].propertyFlags;
        if (!(typeBits & (1u << i)) || (flags & required) != required) continue;
        int score = ((flags & preferred) == preferred ? 2 : 0) + ((flags & avoided) ? 0 : 1);
        if (score > bestScore) {
            bestScore = score;
            best = int(i);
        }
    }
    require(best >= 0, "no Vulkan memory type fits the requested use");
    return uint32_t(best);
}

Allocation Allocator::allocate(const VkMemoryRequirements& requirements, MemoryIntent intent, bool linear) {
    uint32_t type = chooseMemoryType(requirements.memoryTypeBits, intent);
    uint64_t alignment = std::max<uint64_t>(requirements.alignment, 16);
    auto take = [&](uint32_t index) -> std::optional<Allocation> {
        Block& block = blocks_[index];
        auto offset = block.ranges->allocate(requirements.size, alignment);
        if (!offset) return std::nullopt;
        ++liveAllocations_;
        return Allocation{block.memory, *offset, requirements.size, block.mapped ? block.mapped + *offset : nullptr, index};
    };
    for (uint32_t i = 0; i < blocks_.size(); ++i) {
        if (blocks_[i].memory && blocks_[i].memoryType == type && blocks_[i].linear == linear)
            if (auto allocation = take(i)) return *allocation;
    }
    // No room: a new block, large enough for oversized resources.
    uint64_t size = std::max(kBlockSize, (requirements.size + kBlockSize - 1) / kBlockSize * kBlockSize);
    VkMemoryAllocateInfo info{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = size,
        .memoryTypeIndex = type,
    };
    Block block{.memoryType = type, .linear = linear, .ranges = std::make_unique<RangeAllocator>(size)};
    VkResult result = vkAllocateMemory(device_.handle(), &info, nullptr, &block.memory);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw Error("out of GPU memory allocating a " + std::to_string(size >> 20) + " MiB block");
    VK_CHECK_RESULT(result, "vkAllocateMemory");
    if (device_.memoryProperties().memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        void* mapped = nullptr;
        VK_CHECK(vkMapMemory(device_.handle(), block.memory, 0, VK_WHOLE_SIZE, 0, &mapped));
        block.mapped = static_cast<uint8_t*>(mapped);
    }
    uint32_t index = uint32_t(blocks_.size());
    for (uint32_t i = 0; i < blocks_.size(); ++i)
        if (!blocks_[i].memory) index = i; // reuse a released slot
    if (index == blocks_.size()) blocks_.push_back(std::move(block));
    else blocks_[index] = std::move(block);
    return *take(index);
}

void Allocator::free(const Allocation& allocation) {
    if (allocation.block == ~0u) return;
    Block& block = blocks_[allocation.block];
    block.ranges->free(allocation.offset, allocation.size);
    --liveAllocations_;
    // Give oversized blocks back at once; keep standard blocks, they are likely to be reused.
    if (block.ranges->used() == 0 && block.ranges->capacity() > kBlockSize) {
        vkFreeMemory(device_.handle(), block.memory, nullptr);
        block = Block{};
    }
}

MemoryStats Allocator::stats() const {
    MemoryStats stats{.liveAllocations = liveAllocations_};
    for (const Block& block : blocks_) {
        if (!block.memory) continue;
        ++stats.blocks;
        stats.reservedBytes += block.ranges->capacity();
        stats.usedBytes += block.ranges->used();
    }
    return stats;
}

} // namespace sward
