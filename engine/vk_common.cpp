#include "engine/vk_common.h"

#include <cstdio>
#include <string>

namespace sward {

const char* resultName(VkResult result) {
    switch (result) {
#define SWARD_RESULT(name) \
    case name: return #name;
        SWARD_RESULT(VK_SUCCESS)
        SWARD_RESULT(VK_NOT_READY)
        SWARD_RESULT(VK_TIMEOUT)
        SWARD_RESULT(VK_INCOMPLETE)
        SWARD_RESULT(VK_SUBOPTIMAL_KHR)
        SWARD_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        SWARD_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        SWARD_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        SWARD_RESULT(VK_ERROR_DEVICE_LOST)
        SWARD_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        SWARD_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        SWARD_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        SWARD_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        SWARD_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        SWARD_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        SWARD_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        SWARD_RESULT(VK_ERROR_FRAGMENTED_POOL)
        SWARD_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        SWARD_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        SWARD_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        SWARD_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
        SWARD_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef SWARD_RESULT
    default: return "VK_ERROR_(unknown)";
    }
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
    throw Error(std::string("Vulkan call failed with ") + resultName(result) + ": " + call + " (" + file + ":" +
                std::to_string(line) + ")");
}

void logInfo(const std::string& message) { std::fprintf(stderr, "sward: %s\n", message.c_str()); }

} // namespace sward
