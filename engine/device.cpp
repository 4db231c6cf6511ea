#include "engine/device.h"

#include "engine/device_choice.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>

namespace sward {

namespace {

bool hasExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
    return std::any_of(list.begin(), list.end(), [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice physical) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> list(count);
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, list.data());
    return list;
}

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

// A device is usable when it has Vulkan 1.3, one queue family with graphics + compute, and push descriptors; with
// a surface, that family must also present to it. A family with timestamps is preferred (only the benchmarks and
// the viewer's pass times need them: GpuTimers). Returns why not, or "" and the family.
std::string unusableReason(VkPhysicalDevice physical, VkSurfaceKHR surface, uint32_t* family) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) return "Vulkan " + versionString(props.apiVersion) + ", not 1.3";
    if (!hasExtension(deviceExtensions(physical), VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        return "no VK_KHR_push_descriptor";
    if (surface && !hasExtension(deviceExtensions(physical), VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        return "no VK_KHR_swapchain";
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (bool timestamps : {true, false})
        for (uint32_t i = 0; i < count; ++i) {
            VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            VkBool32 present = VK_TRUE;
            if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(physical, i, surface, &present);
            if ((families[i].queueFlags & need) == need && (families[i].timestampValidBits > 0 || !timestamps) &&
                present) {
                *family = i;
                return "";
            }
        }
    return surface ? "no graphics + compute queue that presents to the window" : "no graphics + compute queue";
}

bool usable(VkPhysicalDevice physical, VkSurfaceKHR surface, uint32_t* family) {
    return unusableReason(physical, surface, family).empty();
}

// The plain description device_choice.h chooses from.
DeviceCandidate describe(VkPhysicalDevice physical, uint32_t index, VkSurfaceKHR surface) {
    VkPhysicalDeviceDriverProperties driverProps{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceIDProperties id{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES, .pNext = &driverProps};
    VkPhysicalDeviceProperties2 props2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &id};
    vkGetPhysicalDeviceProperties2(physical, &props2);
    DeviceCandidate c{
        .index = index,
        .name = props2.properties.deviceName,
        .kind = DeviceKind(props2.properties.deviceType),
        .driver = std::string(driverProps.driverName) + " " + driverProps.driverInfo,
        .apiVersion = versionString(props2.properties.apiVersion),
    };
    std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), c.uuid.begin());
    uint32_t family = 0;
    c.unusable = unusableReason(physical, surface, &family);
    return c;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

} // namespace

bool envFlag(const char* name) {
    const char* value = std::getenv(name);
    return value && *value && std::strcmp(value, "0") != 0;
}

Device::Device(const DeviceOptions& options) {
    validation_ = options.validation || envFlag("SWARD_VALIDATION");
    createInstance(options);
    if (options.createSurface) {
        surface_ = options.createSurface(instance_);
        require(surface_ != VK_NULL_HANDLE, "could not create a Vulkan surface for the window");
    }
    std::string filter = options.deviceFilter;
    if (filter.empty() && std::getenv("SWARD_DEVICE")) filter = std::getenv("SWARD_DEVICE");
    pickPhysicalDevice(filter);
    createDevice(options);
    if (!options.quiet) logDevice();
}

Device::Device(const HostVulkan& host)
    : instance_(host.instance), physical_(host.physical), device_(host.device), queue_(host.queue),
      queueFamily_(host.queueFamily), drawIndirectCount_(host.drawIndirectCount), owned_(false) {
    require(instance_ && physical_ && device_ && queue_, "host Vulkan: instance, physical device, device and queue are required");
    uint32_t family = 0;
    require(usable(physical_, VK_NULL_HANDLE, &family),
            "host Vulkan: the physical device lacks Vulkan 1.3, VK_KHR_push_descriptor or a graphics + compute queue");
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    require(queueFamily_ < count && (families[queueFamily_].queueFlags & need) == need,
            "host Vulkan: queue family " + std::to_string(queueFamily_) + " lacks graphics or compute");
    readProperties();
    loadDeviceFunctions();
    if (!host.quiet) logDevice();
}

void Device::logDevice() const {
    logInfo("device: " + name_ + " (" + deviceKindName(DeviceKind(properties_.deviceType)) + "), driver " + driver_ +
            ", Vulkan " + versionString(properties_.apiVersion) + ", UUID " + uuid_ +
            (validation_ ? ", validation on" : "") + (owned_ ? "" : ", the host's"));
}

Device::~Device() {
    if (!owned_) return; // the host's instance and device
    if (device_) vkDestroyDevice(device_, nullptr);
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Device::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<Device*>(user);
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    self->validationMessages_.fetch_add(1);
    std::fprintf(stderr, "sward: validation %s: %s\n", level, data->pMessage);
    return VK_FALSE;
}

void Device::createInstance(const DeviceOptions& options) {
    std::vector<const char*> extensions = options.instanceExtensions;
    std::vector<const char*> layers;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
        .pfnUserCallback = debugCallback,
        .pUserData = this,
    };
    // Synchronization validation catches missing or too-narrow barriers, which the core layer cannot.
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messengerInfo,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    if (validation_) {
        uint32_t count = 0;
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> available(count);
        vkEnumerateInstanceLayerProperties(&count, available.data());
        bool found = std::any_of(available.begin(), available.end(), [](auto& l) {
            return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
        });
        require(found, "validation was requested but VK_LAYER_KHRONOS_validation is not installed "
                       "(Debian package vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkApplicationInfo app{
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "sward",
        .applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
        .pEngineName = "sward",
        .apiVersion = VK_API_VERSION_1_3,
    };
    VkInstanceCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation_ ? &features : nullptr,
        .pApplicationInfo = &app,
        .enabledLayerCount = uint32_t(layers.size()),
        .ppEnabledLayerNames = layers.data(),
        .enabledExtensionCount = uint32_t(extensions.size()),
        .ppEnabledExtensionNames = extensions.data(),
    };
    VkResult result = vkCreateInstance(&info, nullptr, &instance_);
    require(result != VK_ERROR_INCOMPATIBLE_DRIVER,
            "no Vulkan driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
    VK_CHECK_RESULT(result, "vkCreateInstance");
    if (validation_) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        VK_CHECK(create(instance_, &messengerInfo, nullptr, &messenger_));
    }
}

void Device::pickPhysicalDevice(const std::string& filter) {
    std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
    std::vector<DeviceCandidate> candidates;
    for (uint32_t i = 0; i < devices.size(); ++i) candidates.push_back(describe(devices[i], i, surface_));
    physical_ = devices[chooseDevice(candidates, filter)]; // throws, listing the devices, when none is chosen
    require(usable(physical_, surface_, &queueFamily_), "the chosen Vulkan device became unusable");
    readProperties();
}

std::vector<DeviceCandidate> listDevices() {
    VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VkInstance instance = VK_NULL_HANDLE;
    VkResult result = vkCreateInstance(&info, nullptr, &instance);
    require(result != VK_ERROR_INCOMPATIBLE_DRIVER,
            "no Vulkan driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
    VK_CHECK_RESULT(result, "vkCreateInstance");
    std::vector<DeviceCandidate> candidates;
    try {
        std::vector<VkPhysicalDevice> devices = physicalDevices(instance);
        for (uint32_t i = 0; i < devices.size(); ++i) candidates.push_back(describe(devices[i], i, VK_NULL_HANDLE));
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return candidates;
}

void Device::readProperties() {
    VkPhysicalDeviceDriverProperties driverProps{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDevicePushDescriptorPropertiesKHR push{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR, .pNext = &driverProps};
    VkPhysicalDeviceIDProperties id{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES, .pNext = &push};
    VkPhysicalDeviceProperties2 props2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &id};
    vkGetPhysicalDeviceProperties2(physical_, &props2);
    properties_ = props2.properties;
    maxPushDescriptors_ = push.maxPushDescriptors;
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, families.data());
    timestampValidBits_ = queueFamily_ < familyCount ? families[queueFamily_].timestampValidBits : 0;
    std::array<uint8_t, 16> uuid{};
    std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), uuid.begin());
    uuid_ = formatDeviceUuid(uuid);
    name_ = properties_.deviceName;
    driver_ = std::string(driverProps.driverName) + " " + driverProps.driverInfo;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memoryProperties_);
}

uint64_t Device::deviceLocalBytes() const {
    uint64_t largest = 0;
    for (uint32_t i = 0; i < memoryProperties_.memoryHeapCount; ++i)
        if (memoryProperties_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            largest = std::max(largest, uint64_t(memoryProperties_.memoryHeaps[i].size));
    return largest;
}

void Device::requireComputeWorkgroup(const char* shader, uint32_t invocations, uint32_t sharedBytes) const {
    const VkPhysicalDeviceLimits& limits = properties_.limits;
    require(invocations <= limits.maxComputeWorkGroupInvocations && invocations <= limits.maxComputeWorkGroupSize[0] &&
                sharedBytes <= limits.maxComputeSharedMemorySize,
            std::string(shader) + " needs workgroups of " + std::to_string(invocations) + " invocations and " +
                std::to_string(sharedBytes) + " bytes of shared memory; the GPU '" + name_ +
                "' allows maxComputeWorkGroupInvocations " + std::to_string(limits.maxComputeWorkGroupInvocations) +
                ", maxComputeWorkGroupSize.x " + std::to_string(limits.maxComputeWorkGroupSize[0]) +
                ", maxComputeSharedMemorySize " + std::to_string(limits.maxComputeSharedMemorySize));
}

void Device::createDevice(const DeviceOptions& options) {
    VkPhysicalDeviceVulkan12Features supported12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 supported{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &supported12};
    vkGetPhysicalDeviceFeatures2(physical_, &supported);
    drawIndirectCount_ = supported12.drawIndirectCount;
    pipelineStatistics_ = supported.features.pipelineStatisticsQuery;

    VkPhysicalDeviceVulkan13Features features13{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
        .synchronization2 = VK_TRUE,
        .dynamicRendering = VK_TRUE,
        .maintenance4 = VK_TRUE, // required by Vulkan 1.3; glslang's 1.3 target emits LocalSizeId
    };
    VkPhysicalDeviceVulkan12Features features12{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &features13,
        .drawIndirectCount = supported12.drawIndirectCount,
        .storageBuffer8BitAccess = supported12.storageBuffer8BitAccess,
        .shaderInt8 = supported12.shaderInt8,
        .timelineSemaphore = VK_TRUE,
    };
    VkPhysicalDeviceFeatures2 features{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &features12,
        .features = {
            .independentBlend = supported.features.independentBlend,
            .multiDrawIndirect = supported.features.multiDrawIndirect,
            .drawIndirectFirstInstance = supported.features.drawIndirectFirstInstance,
            .depthClamp = supported.features.depthClamp,
            .samplerAnisotropy = supported.features.samplerAnisotropy,
            .pipelineStatisticsQuery = supported.features.pipelineStatisticsQuery, // benchmarks
            .fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics,
            .shaderInt16 = supported.features.shaderInt16,
        },
    };
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = queueFamily_,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    std::vector<const char*> extensions = options.deviceExtensions;
    extensions.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (surface_ && std::none_of(extensions.begin(), extensions.end(), [](const char* e) {
            return std::strcmp(e, VK_KHR_SWAPCHAIN_EXTENSION_NAME) == 0;
        }))
        extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    VkDeviceCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &features,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queueInfo,
        .enabledExtensionCount = uint32_t(extensions.size()),
        .ppEnabledExtensionNames = extensions.data(),
    };
    VK_CHECK(vkCreateDevice(physical_, &info, nullptr, &device_));
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    loadDeviceFunctions();
}

void Device::loadDeviceFunctions() {
    cmdPushDescriptorSet =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
    require(cmdPushDescriptorSet != nullptr, "the device does not expose vkCmdPushDescriptorSetKHR");
}

} // namespace sward
