// Device: Vulkan instance, physical-device choice, logical device, one universal queue, validation.
//
// Headless first: no window or surface is needed. The viewer adds its instance/device extensions through
// DeviceOptions. Requires Vulkan 1.3 (dynamic rendering, synchronization2, timeline semaphores) and
// VK_KHR_push_descriptor, which lavapipe and every current desktop driver provide.
#pragma once

#include "engine/device_choice.h"
#include "engine/vk_common.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sward {

struct DeviceOptions {
    // The `--device` text (engine/device_choice.h): "#N" or "N" an index, an 8-4-4-4-12 hex deviceUUID, else a
    // case-insensitive substring of the device name; empty = automatic choice (discrete > integrated > virtual >
    // CPU). The environment variable SWARD_DEVICE is used when this is empty.
    std::string deviceFilter;
    // Enable VK_LAYER_KHRONOS_validation and the debug messenger. On by default in Debug builds; also forced
    // on by SWARD_VALIDATION=1.
#ifdef NDEBUG
    bool validation = false;
#else
    bool validation = true;
#endif
    std::vector<const char*> instanceExtensions; // extra, e.g. from glfwGetRequiredInstanceExtensions
    std::vector<const char*> deviceExtensions;   // extra, e.g. VK_KHR_swapchain
    bool quiet = false;                          // don't log the chosen device
    // Window output (viewer): creates the surface once the instance exists (e.g. glfwCreateWindowSurface).
    // The device then owns the surface, requires a queue family that can present to it and enables
    // VK_KHR_swapchain. Pass the window system's instance extensions in instanceExtensions.
    std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

// Host-owned Vulkan (docs/integration.md): the application's own instance, device and queue. sward then creates no
// instance or device and destroys none of these. The host must have created `device` for Vulkan 1.3 with
// VK_KHR_push_descriptor and at least the features Device::createDevice enables for itself (synchronization2,
// dynamicRendering, maintenance4, timelineSemaphore, and storageBuffer8BitAccess, shaderInt8, shaderInt16,
// independentBlend, multiDrawIndirect, drawIndirectFirstInstance, depthClamp, samplerAnisotropy,
// fragmentStoresAndAtomics where supported), on a queue family with graphics and compute (and timestamps for GPU
// pass times: GpuTimers). Vulkan requires external synchronisation of a queue: the host must not submit to `queue`
// from another thread while a sward call that submits is running.
struct HostVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    bool drawIndirectCount = false; // the host enabled VkPhysicalDeviceVulkan12Features::drawIndirectCount
    bool quiet = false;             // don't log the device
};

class Device {
public:
    explicit Device(const DeviceOptions& options);
    // The host's device (see HostVulkan): checked to be Vulkan 1.3 with a suitable queue family, never destroyed.
    explicit Device(const HostVulkan& host);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical() const { return physical_; }
    VkDevice handle() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
    // "llvmpipe (LLVM 15.0.6, 256 bits)", driver "llvmpipe Mesa 22.3.6", ...: for logs and dataset manifests.
    const std::string& name() const { return name_; }
    const std::string& driver() const { return driver_; }
    const std::string& uuid() const { return uuid_; } // deviceUUID, 8-4-4-4-12 hex, as `--device` accepts it
    VkSurfaceKHR surface() const { return surface_; } // null without DeviceOptions::createSurface
    bool isCpu() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
    bool hostOwned() const { return !owned_; } // made by the application (HostVulkan)
    bool validationEnabled() const { return validation_; }
    bool supportsDrawIndirectCount() const { return drawIndirectCount_; }
    bool supportsPipelineStatistics() const { return pipelineStatistics_; } // for benchmarks (pipeline_statistics.h)
    // Limits sward queries instead of assuming lavapipe's (docs/release.md, "GPU portability").
    uint32_t maxPushDescriptors() const { return maxPushDescriptors_; }
    uint32_t timestampValidBits() const { return timestampValidBits_; } // of the queue's family; 0: no timestamps
    uint64_t deviceLocalBytes() const; // the largest DEVICE_LOCAL heap
    // Throws naming the device's limits when `shader`'s workgroup of `invocations` (x only) and `sharedBytes` of
    // shared memory exceeds them (Vulkan guarantees only 128 invocations and 16384 bytes).
    void requireComputeWorkgroup(const char* shader, uint32_t invocations, uint32_t sharedBytes) const;

    // Number of validation messages (warnings and errors) seen so far. Tests and tools treat any as failure.
    uint32_t validationMessageCount() const { return validationMessages_.load(); }

    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user);
    void createInstance(const DeviceOptions& options);
    void pickPhysicalDevice(const std::string& filter);
    void createDevice(const DeviceOptions& options);
    void readProperties();
    void loadDeviceFunctions();
    void logDevice() const;

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    std::string name_, driver_, uuid_;
    bool validation_ = false;
    bool drawIndirectCount_ = false;
    bool pipelineStatistics_ = false;
    uint32_t maxPushDescriptors_ = 0, timestampValidBits_ = 0;
    bool owned_ = true; // false: the host's instance and device (HostVulkan), left alive
    std::atomic<uint32_t> validationMessages_{0};
};

// Every physical device the Vulkan loader offers, described for chooseDevice / describeDevices
// (`sward-render --list-devices`); creates and destroys its own instance.
std::vector<DeviceCandidate> listDevices();

// True when the environment variable is set to a non-empty value other than "0".
bool envFlag(const char* name);

} // namespace sward
