// Context: the device, its memory and its submission queue, created and destroyed in the right order.
// Everything in the engine that creates GPU objects takes a Context&.
#pragma once

#include "engine/commands.h"
#include "engine/device.h"
#include "engine/memory.h"

namespace sward {

struct Context {
    explicit Context(const DeviceOptions& options) : device(options), allocator(device), submitter(device) {}
    // Host-owned Vulkan: sward's memory and submissions on the application's device and queue (HostVulkan).
    explicit Context(const HostVulkan& host) : device(host), allocator(device), submitter(device) {}

    VkDevice vk() const { return device.handle(); }

    Device device;
    Allocator allocator;   // destroyed after the submitter has released deferred resources
    Submitter submitter;
};

} // namespace sward
