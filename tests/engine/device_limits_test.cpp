// Device limits (docs/release.md, "GPU portability"): requests beyond the device's own limits are refused with one
// error naming the device and the limit, before any Vulkan call could fail or misbehave.
#include "gpu_test.h"

#include "engine/pipelines.h"
#include "engine/render_target.h"
#include "engine/resources.h"
#include "engine/timestamps.h"

#include <string>

using namespace sward;

namespace {

class DeviceLimits : public sward::test::GpuTest {};

template <typename F> std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_F(DeviceLimits, AnImageWiderThanTheDeviceAllowsNamesItsLimit) {
    const uint32_t largest = ctx->device.properties().limits.maxImageDimension2D;
    const std::string error = errorOf([&] {
        createImage(*ctx,
                    {.format = VK_FORMAT_R8G8B8A8_UNORM, .width = largest + 1, .usage = VK_IMAGE_USAGE_SAMPLED_BIT});
    });
    EXPECT_NE(error.find("a " + std::to_string(largest + 1) + "x1 RGBA8 image is larger than the GPU '" +
                         ctx->device.name() + "' allows"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("maxImageDimension2D " + std::to_string(largest)), std::string::npos) << error;
    Image widest =
        createImage(*ctx, {.format = VK_FORMAT_R8G8B8A8_UNORM, .width = largest, .usage = VK_IMAGE_USAGE_SAMPLED_BIT});
    EXPECT_TRUE(widest);
    destroyImage(*ctx, widest);
}

TEST_F(DeviceLimits, ASampleCountTheDeviceLacksIsRefusedByName) {
    // 64 samples: allowed by Vulkan, offered by no current desktop driver nor lavapipe for a float target.
    const std::string error = errorOf([&] {
        createImage(*ctx, {.format = VK_FORMAT_R16G16B16A16_SFLOAT,
                           .width = 8,
                           .height = 8,
                           .samples = VK_SAMPLE_COUNT_64_BIT,
                           .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT});
    });
    EXPECT_NE(error.find("a 8x8 RGBA16F image with 64 samples: the GPU '" + ctx->device.name() +
                         "' does not support that sample count"),
              std::string::npos)
        << error;
}

TEST_F(DeviceLimits, TheColourAndDepthSamplesSwardUsesAreOfferedAsVulkanRequires) {
    // 1 and 4 samples are required of every device for float colour and depth targets: the check passes them.
    for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT})
        for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_D32_SFLOAT}) {
            const bool depth = format == VK_FORMAT_D32_SFLOAT;
            Image image =
                createImage(*ctx, {.format = format,
                                   .width = 16,
                                   .height = 16,
                                   .samples = samples,
                                   .usage = VkImageUsageFlags(depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                                    : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)});
            EXPECT_TRUE(image);
            destroyImage(*ctx, image);
        }
}

TEST_F(DeviceLimits, AWorkgroupBeyondTheDeviceNamesItsLimits) {
    const VkPhysicalDeviceLimits& limits = ctx->device.properties().limits;
    ctx->device.requireComputeWorkgroup("vegetation_scan.comp", 1024, 16388); // what the scan needs
    const std::string error =
        errorOf([&] { ctx->device.requireComputeWorkgroup("big.comp", limits.maxComputeWorkGroupInvocations + 1, 0); });
    EXPECT_NE(error.find("big.comp needs workgroups of " + std::to_string(limits.maxComputeWorkGroupInvocations + 1) +
                         " invocations and 0 bytes of shared memory; the GPU '" + ctx->device.name() +
                         "' allows maxComputeWorkGroupInvocations " +
                         std::to_string(limits.maxComputeWorkGroupInvocations)),
              std::string::npos)
        << error;
    EXPECT_NE(errorOf([&] {
                  ctx->device.requireComputeWorkgroup("s.comp", 64, limits.maxComputeSharedMemorySize + 1);
              }).find("maxComputeSharedMemorySize " + std::to_string(limits.maxComputeSharedMemorySize)),
              std::string::npos);
}

TEST_F(DeviceLimits, APipelineLayoutBeyondThePushDescriptorLimitIsRefused) {
    const uint32_t limit = ctx->device.maxPushDescriptors();
    EXPECT_GE(limit, 32u); // Vulkan's minimum
    PipelineLayoutDesc layout;
    for (uint32_t b = 0; b <= limit; ++b)
        layout.bindings.push_back(layoutBinding(b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT));
    const std::string error = errorOf([&] { createComputePipeline(ctx->device, "test_roundtrip.comp", layout); });
    EXPECT_NE(error.find("a pipeline layout of " + std::to_string(limit + 1) + " descriptors: the GPU '" +
                         ctx->device.name() + "' pushes at most " + std::to_string(limit) + " (maxPushDescriptors)"),
              std::string::npos)
        << error;
    const uint32_t constants = ctx->device.properties().limits.maxPushConstantsSize;
    EXPECT_NE(errorOf([&] {
                  createComputePipeline(
                      ctx->device, "test_roundtrip.comp",
                      {.pushConstantSize = constants + 4, .pushConstantStages = VK_SHADER_STAGE_COMPUTE_BIT});
              }).find("(maxPushConstantsSize)"),
              std::string::npos);
}

TEST_F(DeviceLimits, ARenderTargetOfMoreColoursThanTheDeviceAllowsIsRefused) {
    const uint32_t limit = ctx->device.properties().limits.maxColorAttachments;
    EXPECT_GE(limit, 5u); // the truth pass with motion flow
    RenderTargetDesc desc{.width = 4, .height = 4};
    desc.colors.resize(limit + 1, {VK_FORMAT_R32_UINT, VkClearColorValue{}});
    const std::string error = errorOf([&] { RenderTarget target(*ctx, desc); });
    EXPECT_NE(error.find("a pass of " + std::to_string(limit + 1) + " colour attachments: the GPU '" +
                         ctx->device.name() + "' allows " + std::to_string(limit) + " (maxColorAttachments)"),
              std::string::npos)
        << error;
}

TEST_F(DeviceLimits, TheDeviceReportsItsTimestampBitsAndDeviceLocalMemory) {
    EXPECT_GT(ctx->device.timestampValidBits(), 0u); // lavapipe and every desktop GPU: GpuTimers works
    EXPECT_LE(ctx->device.timestampValidBits(), 64u);
    EXPECT_GT(ctx->device.deviceLocalBytes(), uint64_t(256) << 20);
    GpuTimers timers(ctx->device, 1);
    ctx->submitter.immediate([&](VkCommandBuffer cmd) {
        timers.reset(cmd);
        timers.begin(cmd, "empty");
        timers.end(cmd);
    });
    const auto times = timers.read();
    ASSERT_EQ(times.size(), 1u);
    EXPECT_GE(times[0].second, 0.0);
    EXPECT_LT(times[0].second, 1000.0); // a masked difference: never a wrapped 2^64 ticks
}
