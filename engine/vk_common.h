// Vulkan error checks and logging shared by the engine.
//
// Tiered checks: VK_CHECK throws sward::Error with file:line and the result name for calls whose failure is
// unrecoverable for the current job (the tool prints it and exits non-zero). Calls that may fail in
// expected ways (swapchain out of date) check their result explicitly at the call site.
#pragma once

#include "common/error.h"

#include <vulkan/vulkan.h>

#include <string>

namespace sward {

const char* resultName(VkResult result);

[[noreturn]] void throwVulkanError(VkResult result, const char* call, const char* file, int line);

#define VK_CHECK(call)                                                                                         \
    do {                                                                                                       \
        VkResult vkCheckResult_ = (call);                                                                      \
        if (vkCheckResult_ != VK_SUCCESS) ::sward::throwVulkanError(vkCheckResult_, #call, __FILE__, __LINE__); \
    } while (0)

// Informational log line on stderr ("sward: ..."), so stdout stays free for machine-readable output.
void logInfo(const std::string& message);

} // namespace sward
