// Vulkan error checks and logging shared by the engine.
//
// Tiered checks: VK_CHECK throws sward::Error for calls whose failure is unrecoverable for the current job (the
// tool prints it and exits non-zero): what failed in words and the result's name, "the GPU ran out of memory while
// creating an image (VK_ERROR_OUT_OF_DEVICE_MEMORY)"; with SWARD_DEBUG=1 the call's text, file and line go to stderr
// first, for developers. Calls that may fail in expected ways (swapchain out of date) check their result explicitly
// at the call site; VK_CHECK_RESULT checks a result kept in a variable, naming the call that returned it.
#pragma once

#include "common/error.h"

#include <vulkan/vulkan.h>

#include <string>

namespace sward {

const char* resultName(VkResult result);

// The user's line for a failed call: "<what the result means> while <the call's verb and object> (<result name>)".
// `call` is the call's text or its name ("vkCreateImage(...)", "vkCreateImage").
std::string vulkanErrorMessage(VkResult result, const char* call);

[[noreturn]] void throwVulkanError(VkResult result, const char* call, const char* file, int line);

#define VK_CHECK(call)                                                                                                 \
    do {                                                                                                               \
        VkResult vkCheckResult_ = (call);                                                                              \
        if (vkCheckResult_ != VK_SUCCESS) ::sward::throwVulkanError(vkCheckResult_, #call, __FILE__, __LINE__);        \
    } while (0)

#define VK_CHECK_RESULT(result, callName)                                                                              \
    do {                                                                                                               \
        if ((result) != VK_SUCCESS) ::sward::throwVulkanError((result), callName, __FILE__, __LINE__);                 \
    } while (0)

// Informational log line on stderr ("sward: ..."), so stdout stays free for machine-readable output.
void logInfo(const std::string& message);

} // namespace sward
