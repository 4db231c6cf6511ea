#include "engine/resources.h"

#include "engine/barriers.h"
#include "engine/context.h"

#include <algorithm>
#include <cstring>

namespace sward {

Buffer createBuffer(Context& ctx, uint64_t size, VkBufferUsageFlags usage, MemoryIntent intent) {
    require(size > 0, "cannot create an empty GPU buffer");
    VkBufferCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    Buffer buffer{.size = size};
    VK_CHECK(vkCreateBuffer(ctx.vk(), &info, nullptr, &buffer.handle));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(ctx.vk(), buffer.handle, &requirements);
    buffer.memory = ctx.allocator.allocate(requirements, intent, /*linear=*/true);
    VK_CHECK(vkBindBufferMemory(ctx.vk(), buffer.handle, buffer.memory.memory, buffer.memory.offset));
    return buffer;
}

void destroyBuffer(Context& ctx, Buffer& buffer) {
    if (!buffer) return;
    vkDestroyBuffer(ctx.vk(), buffer.handle, nullptr);
    ctx.allocator.free(buffer.memory);
    buffer = {};
}

void retireBuffer(Context& ctx, Buffer& buffer) {
    if (!buffer) return;
    ctx.submitter.destroyLater([&ctx, b = buffer]() mutable { destroyBuffer(ctx, b); });
    buffer = {};
}

static VkImageAspectFlags aspectOf(VkFormat format) {
    switch (format) {
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM: return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default: return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

// The formats sward makes images of, by name for error messages.
static std::string formatName(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM: return "RGBA8";
    case VK_FORMAT_R8G8B8A8_SRGB: return "RGBA8 sRGB";
    case VK_FORMAT_B8G8R8A8_UNORM: return "BGRA8";
    case VK_FORMAT_B8G8R8A8_SRGB: return "BGRA8 sRGB";
    case VK_FORMAT_R16G16B16A16_SFLOAT: return "RGBA16F";
    case VK_FORMAT_R32_SFLOAT: return "R32F";
    case VK_FORMAT_R32G32B32A32_SFLOAT: return "RGBA32F";
    case VK_FORMAT_R8_UINT: return "R8UI";
    case VK_FORMAT_R16_UINT: return "R16UI";
    case VK_FORMAT_R32_UINT: return "R32UI";
    case VK_FORMAT_R32G32_UINT: return "RG32UI";
    case VK_FORMAT_R32G32B32A32_UINT: return "RGBA32UI";
    case VK_FORMAT_D32_SFLOAT: return "D32F";
    default: return "VkFormat " + std::to_string(int(format));
    }
}

// The device's own limits for this format, usage and sample count (vkGetPhysicalDeviceImageFormatProperties: it
// includes maxImageDimension2D and framebuffer*SampleCounts), so a request no device could meet or one beyond this
// device is one error naming the device and its limit, not a Vulkan error or a lost device.
static void requireImageSupported(const Device& device, const ImageDesc& desc) {
    const std::string what = "a " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + " " +
                             formatName(desc.format) + " image";
    require(desc.width > 0 && desc.height > 0, what + " is empty");
    VkImageFormatProperties props{};
    VkResult result = vkGetPhysicalDeviceImageFormatProperties(device.physical(), desc.format, VK_IMAGE_TYPE_2D,
                                                               VK_IMAGE_TILING_OPTIMAL, desc.usage, 0, &props);
    require(result == VK_SUCCESS, "the GPU '" + device.name() + "' cannot make " + what + " with this usage");
    require(desc.width <= props.maxExtent.width && desc.height <= props.maxExtent.height,
            what + " is larger than the GPU '" + device.name() + "' allows (" + std::to_string(props.maxExtent.width) +
                "x" + std::to_string(props.maxExtent.height) + ", maxImageDimension2D " +
                std::to_string(device.properties().limits.maxImageDimension2D) + ")");
    require((props.sampleCounts & desc.samples) != 0,
            what + " with " + std::to_string(uint32_t(desc.samples)) + " samples: the GPU '" + device.name() +
                "' does not support that sample count for it (sampleCounts mask " +
                std::to_string(props.sampleCounts) + ")");
    require(std::max(desc.layers, 1u) <= props.maxArrayLayers && desc.mipLevels <= props.maxMipLevels,
            what + " of " + std::to_string(desc.layers) + " layers and " + std::to_string(desc.mipLevels) +
                " levels: the GPU '" + device.name() + "' allows " + std::to_string(props.maxArrayLayers) +
                " layers and " + std::to_string(props.maxMipLevels) + " levels");
}

Image createImage(Context& ctx, const ImageDesc& desc) {
    requireImageSupported(ctx.device, desc);
    VkImageCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = desc.format,
        .extent = {desc.width, desc.height, 1},
        .mipLevels = desc.mipLevels,
        .arrayLayers = std::max(desc.layers, 1u),
        .samples = desc.samples,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = desc.usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    Image image{
        .format = desc.format,
        .extent = {desc.width, desc.height},
        .mipLevels = desc.mipLevels,
        .samples = desc.samples,
        .aspect = aspectOf(desc.format),
    };
    VK_CHECK(vkCreateImage(ctx.vk(), &info, nullptr, &image.handle));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(ctx.vk(), image.handle, &requirements);
    image.memory = ctx.allocator.allocate(requirements, MemoryIntent::DeviceLocal, /*linear=*/false);
    VK_CHECK(vkBindImageMemory(ctx.vk(), image.handle, image.memory.memory, image.memory.offset));
    VkImageViewCreateInfo viewInfo{
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = image.handle,
        .viewType = desc.layers > 0 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D,
        .format = desc.format,
        .subresourceRange = {image.aspect, 0, desc.mipLevels, 0, std::max(desc.layers, 1u)},
    };
    VK_CHECK(vkCreateImageView(ctx.vk(), &viewInfo, nullptr, &image.view));
    return image;
}

void destroyImage(Context& ctx, Image& image) {
    if (!image) return;
    vkDestroyImageView(ctx.vk(), image.view, nullptr);
    vkDestroyImage(ctx.vk(), image.handle, nullptr);
    ctx.allocator.free(image.memory);
    image = {};
}

void retireImage(Context& ctx, Image& image) {
    if (!image) return;
    ctx.submitter.destroyLater([&ctx, i = image]() mutable { destroyImage(ctx, i); });
    image = {};
}

void uploadToBuffer(Context& ctx, const Buffer& dst, uint64_t offset, std::span<const uint8_t> data) {
    if (data.empty()) return;
    require(offset + data.size() <= dst.size, "upload past the end of a GPU buffer");
    Buffer staging = createBuffer(ctx, data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryIntent::Upload);
    std::memcpy(staging.mapped(), data.data(), data.size());
    ctx.submitter.immediate([&](VkCommandBuffer cmd) {
        VkBufferCopy region{.srcOffset = 0, .dstOffset = offset, .size = data.size()};
        vkCmdCopyBuffer(cmd, staging.handle, dst.handle, 1, &region);
        // Later users of the buffer (any stage) see the copy.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
    });
    destroyBuffer(ctx, staging);
}

Buffer createBufferWithData(Context& ctx, std::span<const uint8_t> data, VkBufferUsageFlags usage) {
    Buffer buffer = createBuffer(ctx, data.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::DeviceLocal);
    uploadToBuffer(ctx, buffer, 0, data);
    return buffer;
}

Image createImageWithData(Context& ctx, ImageDesc desc, std::span<const std::span<const uint8_t>> levels) {
    require(levels.size() == desc.mipLevels, "one data span per mip level");
    desc.usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Image image = createImage(ctx, desc);
    uint64_t total = 0;
    for (std::span<const uint8_t> level : levels) total += level.size();
    Buffer staging = createBuffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryIntent::Upload);
    std::vector<VkBufferImageCopy> regions;
    uint64_t offset = 0;
    for (uint32_t level = 0; level < desc.mipLevels; ++level) {
        std::memcpy(staging.mapped() + offset, levels[level].data(), levels[level].size());
        regions.push_back({.bufferOffset = offset,
                           .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, std::max(desc.layers, 1u)},
                           .imageExtent = {std::max(desc.width >> level, 1u), std::max(desc.height >> level, 1u), 1}});
        offset += levels[level].size();
    }
    ctx.submitter.immediate([&](VkCommandBuffer cmd) {
        discardToCopyDstBarrier(cmd, image.handle, VK_IMAGE_ASPECT_COLOR_BIT);
        vkCmdCopyBufferToImage(cmd, staging.handle, image.handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        copyToFragmentSampledBarrier(cmd, image.handle, VK_IMAGE_ASPECT_COLOR_BIT);
    });
    destroyBuffer(ctx, staging);
    return image;
}

VkSampler createLinearSampler(Context& ctx, uint32_t mipLevels, VkSamplerAddressMode address) {
    VkSamplerCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_LINEAR,
        .minFilter = VK_FILTER_LINEAR,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR,
        .addressModeU = address,
        .addressModeV = address,
        .addressModeW = address,
        .maxLod = float(mipLevels),
    };
    VkSampler sampler = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSampler(ctx.vk(), &info, nullptr, &sampler));
    return sampler;
}

std::vector<uint8_t> readBuffer(Context& ctx, const Buffer& src, uint64_t offset, uint64_t size) {
    require(offset + size <= src.size, "readback past the end of a GPU buffer");
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    ctx.submitter.immediate([&](VkCommandBuffer cmd) {
        // Whatever wrote the buffer before (compute, transfer) must finish before the copy reads it.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy region{.srcOffset = offset, .dstOffset = 0, .size = size};
        vkCmdCopyBuffer(cmd, src.handle, staging.handle, 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_HOST_READ_BIT);
    });
    std::vector<uint8_t> data(staging.mapped(), staging.mapped() + size);
    destroyBuffer(ctx, staging);
    return data;
}

uint32_t formatBytes(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: return 4;
    case VK_FORMAT_R16_UINT: return 2;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_UINT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw Error("formatBytes: unsupported format " + std::to_string(int(format)));
    }
}

} // namespace sward
