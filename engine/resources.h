// Resources: buffers and images with sub-allocated memory, and copies between them and the host.
//
// Buffer and Image are plain handles (copyable values). Ownership is explicit: destroy() frees at once
// (caller guarantees the GPU is done), retire() defers the free until the work submitted so far completes.
#pragma once

#include "engine/memory.h"

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

struct Context;

struct Buffer {
    VkBuffer handle = VK_NULL_HANDLE;
    Allocation memory;
    uint64_t size = 0;
    // Host pointer for Upload / Readback buffers (persistently mapped), null for device-local ones.
    uint8_t* mapped() const { return memory.mapped; }
    explicit operator bool() const { return handle != VK_NULL_HANDLE; }
};

struct Image {
    VkImage handle = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    Allocation memory;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    uint32_t mipLevels = 1;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    explicit operator bool() const { return handle != VK_NULL_HANDLE; }
};

Buffer createBuffer(Context& ctx, uint64_t size, VkBufferUsageFlags usage, MemoryIntent intent);
void destroyBuffer(Context& ctx, Buffer& buffer);
void retireBuffer(Context& ctx, Buffer& buffer);

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1, height = 1;
    uint32_t mipLevels = 1;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageUsageFlags usage = 0;
    uint32_t layers = 0; // 0: a plain 2D image; n >= 1: a 2D array image of n layers with a 2D_ARRAY view
};
Image createImage(Context& ctx, const ImageDesc& desc);
void destroyImage(Context& ctx, Image& image);
void retireImage(Context& ctx, Image& image);

// Copies `data` into a device-local buffer through a temporary staging buffer, and waits. For load-time data.
Buffer createBufferWithData(Context& ctx, std::span<const uint8_t> data, VkBufferUsageFlags usage);
// The bytes of a vector of plain records (vertices, indices, tables), for createBufferWithData and uploadToBuffer.
template <typename T> std::span<const uint8_t> bytesOf(const std::vector<T>& v) {
    return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}
// Creates a sampled image (desc.usage gains SAMPLED | TRANSFER_DST) and fills mip level i from levels[i] (an array
// image: every layer of that level, one after the other) through one staging buffer, and waits; the image ends in
// SHADER_READ_ONLY_OPTIMAL, visible to fragment shaders.
Image createImageWithData(Context& ctx, ImageDesc desc, std::span<const std::span<const uint8_t>> levels);
// A trilinear sampler over `mipLevels` levels, clamped to the edge or repeating (the caller destroys it).
VkSampler createLinearSampler(Context& ctx, uint32_t mipLevels,
                              VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
// Writes `data` at `offset` of `dst` through a staging buffer (one submission, waits).
void uploadToBuffer(Context& ctx, const Buffer& dst, uint64_t offset, std::span<const uint8_t> data);
// Reads `size` bytes of a buffer back to the host (one submission, waits).
std::vector<uint8_t> readBuffer(Context& ctx, const Buffer& src, uint64_t offset, uint64_t size);

// Bytes per texel for the formats the engine reads back.
uint32_t formatBytes(VkFormat format);

} // namespace sward
