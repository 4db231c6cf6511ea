// VK_CHECK's error line (engine/vk_common.h): what failed in words and the result's name for the user; the call's
// text and source line only on stderr with SWARD_DEBUG (no device needed).
#include "common/error.h"
#include "engine/vk_common.h"

#include <gtest/gtest.h>

#include <cstdlib>

using namespace sward;

namespace {

std::string errorOf(VkResult result, const char* call) {
    try {
        throwVulkanError(result, call, "/src/engine/resources.cpp", 123);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(VulkanError, SaysWhatFailedInWordsWithoutTheCallOrSourcePath) {
    unsetenv("SWARD_DEBUG");
    testing::internal::CaptureStderr();
    const std::string message =
        errorOf(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkCreateImage(device_.handle(), &info, nullptr, &image)");
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(message, "the GPU ran out of memory while creating an image (VK_ERROR_OUT_OF_DEVICE_MEMORY)");
}

TEST(VulkanError, NamesTheCallsVerbAndObject) {
    EXPECT_EQ(
        vulkanErrorMessage(VK_ERROR_OUT_OF_HOST_MEMORY, "vkAllocateCommandBuffers(device, &info, &cmd)"),
        "the Vulkan driver ran out of host memory while allocating command buffers (VK_ERROR_OUT_OF_HOST_MEMORY)");
    EXPECT_EQ(vulkanErrorMessage(VK_ERROR_DEVICE_LOST, "vkQueueSubmit(queue, 1, &submit, fence)"),
              "the GPU was lost (a driver reset or crash) while submitting work to the GPU (VK_ERROR_DEVICE_LOST)");
    EXPECT_EQ(vulkanErrorMessage(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory"),
              "the GPU ran out of memory while allocating memory (VK_ERROR_OUT_OF_DEVICE_MEMORY)");
    EXPECT_EQ(vulkanErrorMessage(VK_ERROR_INITIALIZATION_FAILED, "vkCreateSwapchainKHR(device, &info, nullptr, &s)"),
              "the Vulkan driver failed to initialise while creating a swapchain (VK_ERROR_INITIALIZATION_FAILED)");
    EXPECT_EQ(vulkanErrorMessage(VK_ERROR_SURFACE_LOST_KHR, "glfwCreateWindowSurface(instance, window, nullptr, &s)"),
              "the window's surface was lost in glfwCreateWindowSurface (VK_ERROR_SURFACE_LOST_KHR)");
}

TEST(VulkanError, SwardDebugPrintsTheCallAndItsSourceLineOnStderr) {
    setenv("SWARD_DEBUG", "1", 1);
    testing::internal::CaptureStderr();
    const std::string message = errorOf(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkCreateBuffer(device, &info, nullptr, &b)");
    const std::string debug = testing::internal::GetCapturedStderr();
    unsetenv("SWARD_DEBUG");
    EXPECT_EQ(debug, "sward: debug: vkCreateBuffer(device, &info, nullptr, &b) returned VK_ERROR_OUT_OF_DEVICE_MEMORY "
                     "at /src/engine/resources.cpp:123\n");
    EXPECT_EQ(message.find("resources.cpp"), std::string::npos) << message;
}
