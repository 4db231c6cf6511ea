// Device choice: which physical device a `--device` text (or SWARD_DEVICE) names, as a pure function over plain
// descriptions of the candidates, so its rules are tested without Vulkan (tests/engine/device_choice_test.cpp).
//
// The text is one of:
//   ""                      automatic: the usable device of the best type (discrete > integrated > virtual > CPU),
//                           the lowest index among equals
//   "#N" or "N" (digits)    the device of index N in the Vulkan loader's enumeration order (`--list-devices`)
//   8-4-4-4-12 hex digits   the device whose VkPhysicalDeviceIDProperties::deviceUUID this is (any case)
//   anything else           a case-insensitive substring of the device name; a text equal to a whole name picks
//                           only the devices of exactly that name. Among several usable matches the best type
//                           wins; matches of the same best type are ambiguous (an error naming them: pick one
//                           by index or UUID), so two identical GPUs are never chosen between silently.
// Digits are an index, never a name: names such as "GeForce RTX 4090" are found by any non-numeric part.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Vulkan's VkPhysicalDeviceType values, so the choice needs no Vulkan header.
enum class DeviceKind : uint32_t { Other = 0, IntegratedGpu = 1, DiscreteGpu = 2, VirtualGpu = 3, Cpu = 4 };

struct DeviceCandidate {
    uint32_t index = 0; // position in vkEnumeratePhysicalDevices
    std::string name;   // VkPhysicalDeviceProperties::deviceName
    DeviceKind kind = DeviceKind::Other;
    std::array<uint8_t, 16> uuid{}; // VkPhysicalDeviceIDProperties::deviceUUID
    std::string driver;             // "llvmpipe Mesa 22.3.6": for the list only
    std::string apiVersion;         // "1.3.230": for the list only
    std::string unusable;           // empty when sward can run on it, else why not ("no Vulkan 1.3")
};

// The tools' help for `--device`.
inline constexpr const char* kDeviceOptionHelp =
    "Vulkan device: #N (index), its UUID, or a name substring; default SWARD_DEVICE, else the best GPU "
    "(sward-render --list-devices lists them)";

// "d3f2a8c0-1b2e-4c5d-8e9f-0a1b2c3d4e5f": the usual 8-4-4-4-12 lowercase hex form.
std::string formatDeviceUuid(const std::array<uint8_t, 16>& uuid);
// "discrete GPU", "CPU", ...
const char* deviceKindName(DeviceKind kind);
// The position in `candidates` of the device `text` selects; throws Error with one message that lists every
// candidate (index, name, type, UUID, why unusable) when it selects none, an unusable one, or several.
size_t chooseDevice(const std::vector<DeviceCandidate>& candidates, const std::string& text);
// One line per candidate, for `sward-render --list-devices`: "#0  <uuid>  CPU  llvmpipe (...)  driver ... Vulkan
// 1.3.230", "(not usable: ...)" or "(automatic choice)" after it.
std::string describeDevices(const std::vector<DeviceCandidate>& candidates);

} // namespace sward
