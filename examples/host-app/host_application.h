// The host side of examples/host-app (and of the HostVulkan GPU test): an application bringing up its own Vulkan
// instance (validation layer and its own messenger, counting messages), device and queue, as any engine does before
// it meets sward. Only Vulkan here; what sward needs of the device is listed at sward::HostVulkan (engine/device.h).
#pragma once

#include "engine/device.h"

#include <cstdio>
#include <string>

namespace host {

inline void check(VkResult result) {
    if (result != VK_SUCCESS) throw sward::Error(std::string("host Vulkan call failed: ") + sward::resultName(result));
}

// What a host application does at start-up, reduced to what sward needs (engine/device.h lists it).
struct HostApplication {
    HostApplication() {
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .apiVersion = VK_API_VERSION_1_3};
        // Synchronization validation too: sward's barriers and the host's must order every hazard between them.
        const VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
        VkValidationFeaturesEXT features{.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                         .enabledValidationFeatureCount = 1,
                                         .pEnabledValidationFeatures = &syncValidation};
        VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pNext = &features,
                                  .pApplicationInfo = &app,
                                  .enabledLayerCount = 1, .ppEnabledLayerNames = &layer,
                                  .enabledExtensionCount = 1, .ppEnabledExtensionNames = &extension};
        check(vkCreateInstance(&info, nullptr, &instance));
        VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
            .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
            .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
            .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT,
            .pfnUserCallback = [](VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) -> VkBool32 {
                std::fprintf(stderr, "host validation: %s\n", data->pMessage);
                ++*static_cast<int*>(user);
                return VK_FALSE;
            },
            .pUserData = &messages};
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        check(create(instance, &messengerInfo, nullptr, &messenger));
        uint32_t count = 1;
        vkEnumeratePhysicalDevices(instance, &count, &physical); // lavapipe in CI: the first device will do
        createDevice();
    }
    void createDevice() {
        VkPhysicalDeviceVulkan12Features supported12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceFeatures2 supported{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &supported12};
        vkGetPhysicalDeviceFeatures2(physical, &supported);
        VkPhysicalDeviceVulkan13Features features13{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                                    .synchronization2 = VK_TRUE, .dynamicRendering = VK_TRUE,
                                                    .maintenance4 = VK_TRUE};
        VkPhysicalDeviceVulkan12Features features12 = supported12; // everything the device has, as a host might
        features12.pNext = &features13;
        VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &features12,
                                           .features = supported.features};
        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = 0,
                                          .queueCount = 1, .pQueuePriorities = &priority};
        const char* extension = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
        VkDeviceCreateInfo info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &features,
                                .queueCreateInfoCount = 1, .pQueueCreateInfos = &queueInfo,
                                .enabledExtensionCount = 1, .ppEnabledExtensionNames = &extension};
        check(vkCreateDevice(physical, &info, nullptr, &device));
        vkGetDeviceQueue(device, 0, 0, &queue);
        drawIndirectCount = supported12.drawIndirectCount;
    }
    ~HostApplication() {
        vkDestroyDevice(device, nullptr);
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance, messenger, nullptr);
        vkDestroyInstance(instance, nullptr);
    }
    sward::HostVulkan handles() const {
        return {.instance = instance, .physical = physical, .device = device, .queueFamily = 0, .queue = queue,
                .drawIndirectCount = drawIndirectCount, .quiet = true};
    }
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    bool drawIndirectCount = false;
    int messages = 0;
};

} // namespace host
