#include "engine/vk_common.h"

#include "engine/device.h" // envFlag

#include <cctype>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace sward {

const char* resultName(VkResult result) {
    switch (result) {
#define SWARD_RESULT(name)                                                                                             \
    case name:                                                                                                         \
        return #name;
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
    default:
        return "VK_ERROR_(unknown)";
    }
}

namespace {

// What a failed result means, in words a user can act on.
const char* resultMeaning(VkResult result) {
    switch (result) {
    case VK_TIMEOUT:
        return "the GPU did not finish in time";
    case VK_ERROR_OUT_OF_HOST_MEMORY:
        return "the Vulkan driver ran out of host memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
        return "the GPU ran out of memory";
    case VK_ERROR_INITIALIZATION_FAILED:
        return "the Vulkan driver failed to initialise";
    case VK_ERROR_DEVICE_LOST:
        return "the GPU was lost (a driver reset or crash)";
    case VK_ERROR_MEMORY_MAP_FAILED:
        return "the driver could not map GPU memory";
    case VK_ERROR_LAYER_NOT_PRESENT:
        return "a Vulkan layer is not installed (validation: vulkan-validationlayers)";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
        return "the device lacks a Vulkan extension sward needs";
    case VK_ERROR_FEATURE_NOT_PRESENT:
        return "the device lacks a Vulkan feature sward needs";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
        return "no compatible Vulkan driver was found";
    case VK_ERROR_TOO_MANY_OBJECTS:
        return "the driver's limit of Vulkan objects was reached";
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
        return "the GPU does not support an image format sward needs";
    case VK_ERROR_FRAGMENTED_POOL:
    case VK_ERROR_OUT_OF_POOL_MEMORY:
        return "a descriptor pool ran out of room";
    case VK_ERROR_SURFACE_LOST_KHR:
        return "the window's surface was lost";
    case VK_ERROR_NATIVE_WINDOW_IN_USE_KHR:
        return "the window is in use by another program";
    case VK_ERROR_OUT_OF_DATE_KHR:
        return "the window's swapchain is out of date";
    case VK_ERROR_VALIDATION_FAILED_EXT:
        return "the validation layer refused a call";
    default:
        return "the Vulkan driver reported an error";
    }
}

// "while creating an image view" from "vkCreateImageView(device, ...)": the call's verb and object in words, for
// the user's line (the call text and its source line are for developers, SWARD_DEBUG).
std::string whileDoing(const std::string& call) {
    const std::string name = call.substr(0, call.find('('));
    if (name.rfind("vk", 0) != 0) return "in " + name;
    std::string stem = name.substr(2);
    for (const char* suffix : {"KHR", "EXT"})
        if (stem.size() > 3 && stem.compare(stem.size() - 3, 3, suffix) == 0) stem.resize(stem.size() - 3);
    std::vector<std::string> words;
    for (char c : stem) {
        if (std::isupper((unsigned char)c) || words.empty()) words.emplace_back();
        words.back() += char(std::tolower((unsigned char)c));
    }
    static const std::pair<const char*, const char*> kPhrases[] = {{"queue submit", "submitting work to the GPU"},
                                                                   {"queue wait idle", "waiting for the GPU"},
                                                                   {"device wait idle", "waiting for the GPU"},
                                                                   {"queue present", "presenting an image"},
                                                                   {"acquire next image", "acquiring a window image"}};
    std::string joined;
    for (const std::string& w : words) joined += (joined.empty() ? "" : " ") + w;
    for (const auto& [phrase, doing] : kPhrases)
        if (joined == phrase) return std::string("while ") + doing;
    static const std::pair<const char*, const char*> kVerbs[] = {
        {"create", "creating"},  {"allocate", "allocating"}, {"bind", "binding"},  {"map", "mapping"},
        {"begin", "beginning"},  {"end", "ending"},          {"get", "querying"},  {"enumerate", "listing"},
        {"wait", "waiting for"}, {"reset", "resetting"},     {"flush", "flushing"}};
    for (const auto& [verb, doing] : kVerbs) {
        if (words.size() < 2 || words[0] != verb) continue;
        const std::string object = joined.substr(words[0].size() + 1);
        const bool countable = words.back() != "memory" && words.back().back() != 's';
        const char* article = !countable ? "" : std::strchr("aeiou", object[0]) ? "an " : "a ";
        return std::string("while ") + doing + " " + article + object;
    }
    return "in " + name;
}

} // namespace

std::string vulkanErrorMessage(VkResult result, const char* call) {
    return std::string(resultMeaning(result)) + " " + whileDoing(call) + " (" + resultName(result) + ")";
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
    if (envFlag("SWARD_DEBUG"))
        std::fprintf(stderr, "sward: debug: %s returned %s at %s:%d\n", call, resultName(result), file, line);
    throw Error(vulkanErrorMessage(result, call));
}

void logInfo(const std::string& message) {
    std::fprintf(stderr, "sward: %s\n", message.c_str());
}

} // namespace sward
