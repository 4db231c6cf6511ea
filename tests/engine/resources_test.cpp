#include "gpu_test.h"

#include "engine/barriers.h"
#include "engine/pipelines.h"
#include "engine/resources.h"
#include "engine/timestamps.h"
#include "shared/config.h"

#include <cstring>
#include <numeric>

using namespace sward;
using sward::test::GpuTest;

TEST_F(GpuTest, ComputeRoundTripThroughPushDescriptorsAndSpecialization) {
    const uint32_t count = 1000;
    std::vector<uint32_t> input(count);
    std::iota(input.begin(), input.end(), 5u);
    Buffer src = createBufferWithData(*ctx, {reinterpret_cast<uint8_t*>(input.data()), count * 4},
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer dst = createBuffer(*ctx, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              MemoryIntent::DeviceLocal);
    Pipeline pipeline =
        createComputePipeline(ctx->device, "test_roundtrip.comp",
                              {.bindings = {layoutBinding(gpu::kTestBindingInput, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                          VK_SHADER_STAGE_COMPUTE_BIT),
                                            layoutBinding(gpu::kTestBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                          VK_SHADER_STAGE_COMPUTE_BIT)},
                               .pushConstantSize = 8,
                               .pushConstantStages = VK_SHADER_STAGE_COMPUTE_BIT},
                              {/* SCALE= */ 3});
    GpuTimers timers(ctx->device, 4);
    ctx->submitter.immediate([&](VkCommandBuffer cmd) {
        timers.reset(cmd);
        timers.begin(cmd, "roundtrip");
        bindPipeline(cmd, pipeline);
        pushDescriptors(
            ctx->device, cmd, pipeline,
            {storageBuffer(gpu::kTestBindingInput, src.handle), storageBuffer(gpu::kTestBindingOutput, dst.handle)});
        uint32_t push[2] = {count, 7};
        pushConstants(cmd, pipeline, push, sizeof push);
        vkCmdDispatch(cmd, groupCount(count, gpu::kComputeGroupSize), 1, 1);
        timers.end(cmd);
    });
    std::vector<uint8_t> bytes = readBuffer(*ctx, dst, 0, count * 4);
    std::vector<uint32_t> output(count);
    std::memcpy(output.data(), bytes.data(), bytes.size());
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(output[i], input[i] * 3 + 7) << "at " << i;

    auto passes = timers.read();
    ASSERT_EQ(passes.size(), 1u);
    EXPECT_EQ(passes[0].first, "roundtrip");
    EXPECT_GE(passes[0].second, 0.0);

    destroyPipeline(ctx->device, pipeline);
    destroyBuffer(*ctx, src);
    destroyBuffer(*ctx, dst);
}

TEST_F(GpuTest, BuffersAreSubAllocatedFromFewBlocks) {
    std::vector<Buffer> buffers;
    for (int i = 0; i < 200; ++i)
        buffers.push_back(createBuffer(*ctx, 4096 + i * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryIntent::DeviceLocal));
    MemoryStats stats = ctx->allocator.stats();
    EXPECT_EQ(stats.liveAllocations, 200u);
    EXPECT_LE(stats.blocks, 2u) << "every buffer got its own vkAllocateMemory";
    for (size_t i = 1; i < buffers.size(); ++i) {
        if (buffers[i].memory.memory != buffers[i - 1].memory.memory) continue;
        EXPECT_GE(buffers[i].memory.offset, buffers[i - 1].memory.offset + buffers[i - 1].size) << "ranges overlap";
    }
    for (Buffer& b : buffers) destroyBuffer(*ctx, b);
    EXPECT_EQ(ctx->allocator.stats().usedBytes, 0u);
}

TEST_F(GpuTest, DeferredDestructionWaitsForSubmittedWork) {
    Buffer buffer = createBuffer(*ctx, 1024, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::DeviceLocal);
    VkCommandBuffer cmd = ctx->submitter.begin();
    vkCmdFillBuffer(cmd, buffer.handle, 0, VK_WHOLE_SIZE, 0);
    uint64_t serial = ctx->submitter.submit(cmd);
    bool destroyed = false;
    ctx->submitter.destroyLater([&] {
        destroyed = true;
        destroyBuffer(*ctx, buffer);
    });
    if (ctx->submitter.completed() < serial) {
        EXPECT_FALSE(destroyed);
    }
    ctx->submitter.wait(serial);
    EXPECT_TRUE(destroyed);
}

TEST(Validation, AnInvalidCallIsReported) {
    // The guard every other GPU test relies on: a real validation error must be counted.
    Context ctx(DeviceOptions{.validation = true, .quiet = true});
    VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                            .size = 0, // VUID-VkBufferCreateInfo-size-00912
                            .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};
    VkBuffer buffer = VK_NULL_HANDLE;
    testing::internal::CaptureStderr();
    vkCreateBuffer(ctx.vk(), &info, nullptr, &buffer);
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_GE(ctx.device.validationMessageCount(), 1u);
    EXPECT_NE(err.find("00912"), std::string::npos);
    if (buffer) vkDestroyBuffer(ctx.vk(), buffer, nullptr);
}
