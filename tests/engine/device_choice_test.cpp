// Device choice (engine/device_choice.h): the `--device` rules on hand-made candidate lists, no Vulkan; and the
// same rules on the machine's real devices (lavapipe in CI) by index, UUID and name.
#include "common/error.h"
#include "engine/device.h"
#include "engine/device_choice.h"

#include <gtest/gtest.h>

using namespace sward;

namespace {

std::array<uint8_t, 16> uuidOf(uint8_t seed) {
    std::array<uint8_t, 16> uuid{};
    for (size_t i = 0; i < uuid.size(); ++i) uuid[i] = uint8_t(seed * 16 + i);
    return uuid;
}

DeviceCandidate candidate(uint32_t index, const std::string& name, DeviceKind kind, std::string unusable = "") {
    return DeviceCandidate{.index = index,
                           .name = name,
                           .kind = kind,
                           .uuid = uuidOf(uint8_t(index + 1)),
                           .driver = "test",
                           .apiVersion = "1.3.0",
                           .unusable = std::move(unusable)};
}

// A machine with lavapipe, an integrated and a discrete GPU, and an old GPU without Vulkan 1.3.
std::vector<DeviceCandidate> machine() {
    return {candidate(0, "llvmpipe (LLVM 15.0.6, 256 bits)", DeviceKind::Cpu),
            candidate(1, "AMD Radeon Graphics (RADV RENOIR)", DeviceKind::IntegratedGpu),
            candidate(2, "NVIDIA GeForce RTX 4090", DeviceKind::DiscreteGpu),
            candidate(3, "NVIDIA GeForce GTX 580", DeviceKind::DiscreteGpu, "Vulkan 1.2.0, not 1.3")};
}

std::string errorOf(const std::vector<DeviceCandidate>& candidates, const std::string& text) {
    try {
        chooseDevice(candidates, text);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(DeviceChoice, UuidIsPrintedAsEightFourFourFourTwelveLowercaseHex) {
    EXPECT_EQ(formatDeviceUuid(uuidOf(0xa)), "a0a1a2a3-a4a5-a6a7-a8a9-aaabacadaeaf");
}

TEST(DeviceChoice, EmptyTextPicksTheBestUsableTypeFirstOfEquals) {
    EXPECT_EQ(chooseDevice(machine(), ""), 2u); // the usable discrete GPU, not the unusable one
    std::vector<DeviceCandidate> twins = {candidate(0, "GPU A", DeviceKind::DiscreteGpu),
                                          candidate(1, "GPU A", DeviceKind::DiscreteGpu)};
    EXPECT_EQ(chooseDevice(twins, ""), 0u);
    EXPECT_EQ(chooseDevice({candidate(0, "V", DeviceKind::VirtualGpu), candidate(1, "C", DeviceKind::Cpu)}, ""), 0u);
}

TEST(DeviceChoice, NameIsACaseInsensitiveSubstring) {
    EXPECT_EQ(chooseDevice(machine(), "LLVMPIPE"), 0u);
    EXPECT_EQ(chooseDevice(machine(), "radv"), 1u);
    EXPECT_EQ(chooseDevice(machine(), "RTX 4090"), 2u);
    // Digits alone are an index, never a name: "4090" is device #4090, which does not exist.
    EXPECT_NE(errorOf(machine(), "4090").find("no Vulkan device matches '4090'"), std::string::npos);
}

TEST(DeviceChoice, NameMatchingSeveralTypesTakesTheBestAndSkipsUnusable) {
    EXPECT_EQ(chooseDevice(machine(), "nvidia"), 2u); // the GTX 580 matches too but lacks Vulkan 1.3
    EXPECT_EQ(chooseDevice(machine(), "a"), 2u);      // every device: the discrete GPU
}

TEST(DeviceChoice, NameMatchingTwoDevicesOfTheSameTypeIsAnErrorNamingBoth) {
    std::vector<DeviceCandidate> twins = {candidate(0, "NVIDIA H100", DeviceKind::DiscreteGpu),
                                          candidate(1, "NVIDIA H100", DeviceKind::DiscreteGpu)};
    std::string error = errorOf(twins, "h100");
    EXPECT_NE(error.find("matches 2 devices of the same type (#0 'NVIDIA H100', #1 'NVIDIA H100')"), std::string::npos)
        << error;
    EXPECT_NE(error.find("by index (#N) or UUID"), std::string::npos) << error;
    EXPECT_EQ(chooseDevice(twins, "#1"), 1u);
    EXPECT_EQ(chooseDevice(twins, formatDeviceUuid(twins[1].uuid)), 1u);
}

TEST(DeviceChoice, AWholeNameWinsOverLongerNamesContainingIt) {
    std::vector<DeviceCandidate> list = {candidate(0, "GPU 4090 Ti", DeviceKind::DiscreteGpu),
                                         candidate(1, "gpu 4090", DeviceKind::DiscreteGpu)};
    EXPECT_EQ(chooseDevice(list, "GPU 4090"), 1u);
    EXPECT_NE(errorOf(list, "gpu 40").find("matches 2 devices"), std::string::npos);
}

TEST(DeviceChoice, IndexWithOrWithoutHash) {
    EXPECT_EQ(chooseDevice(machine(), "#0"), 0u);
    EXPECT_EQ(chooseDevice(machine(), "1"), 1u);
    EXPECT_EQ(chooseDevice(machine(), "#2"), 2u);
}

TEST(DeviceChoice, UuidInAnyCase) {
    EXPECT_EQ(chooseDevice(machine(), "20212223-2425-2627-2829-2a2b2c2d2e2f"), 1u);
    EXPECT_EQ(chooseDevice(machine(), "20212223-2425-2627-2829-2A2B2C2D2E2F"), 1u);
}

TEST(DeviceChoice, AUuidOfTwoDevicesIsAnErrorAskingForTheIndex) {
    std::vector<DeviceCandidate> twice = {candidate(0, "llvmpipe", DeviceKind::Cpu),
                                          candidate(1, "llvmpipe", DeviceKind::Cpu)};
    twice[1].uuid = twice[0].uuid; // one driver listed by two ICD files
    EXPECT_NE(
        errorOf(twice, formatDeviceUuid(twice[0].uuid)).find("is the UUID of 2 devices: choose one by index (#N)"),
        std::string::npos);
    EXPECT_EQ(chooseDevice(twice, "#1"), 1u);
}

TEST(DeviceChoice, AnUnusableDeviceNamedByIndexOrUuidIsRefusedWithTheReason) {
    EXPECT_NE(errorOf(machine(), "#3").find("#3 'NVIDIA GeForce GTX 580' is not usable: Vulkan 1.2.0, not 1.3"),
              std::string::npos);
    EXPECT_NE(errorOf(machine(), formatDeviceUuid(machine()[3].uuid)).find("is not usable"), std::string::npos);
    EXPECT_NE(errorOf(machine(), "gtx 580").find("every Vulkan device matching 'gtx 580' is unusable"),
              std::string::npos);
}

TEST(DeviceChoice, NoMatchListsEveryDeviceWithIndexTypeAndUuid) {
    std::string error = errorOf(machine(), "no-such-gpu");
    EXPECT_EQ(error.rfind("no Vulkan device matches 'no-such-gpu' (available: #0 'llvmpipe (LLVM 15.0.6, 256 bits)' "
                          "CPU 10111213-1415-1617-1819-1a1b1c1d1e1f, #1 ",
                          0),
              0u)
        << error;
    EXPECT_NE(error.find("#3 'NVIDIA GeForce GTX 580' discrete GPU 40414243-4445-4647-4849-4a4b4c4d4e4f (not usable: "
                         "Vulkan 1.2.0, not 1.3))"),
              std::string::npos)
        << error;
    EXPECT_NE(errorOf(machine(), "#4").find("no Vulkan device matches '#4'"), std::string::npos);
    EXPECT_NE(errorOf(machine(), "99999999999").find("no Vulkan device matches"), std::string::npos);
    EXPECT_NE(errorOf(machine(), "00000000-0000-0000-0000-000000000000").find("no Vulkan device matches"),
              std::string::npos);
    EXPECT_NE(errorOf(machine(), "#x").find("'#' must be followed by a device index"), std::string::npos);
}

TEST(DeviceChoice, NoUsableDeviceAtAllIsOneErrorListingThem) {
    std::string error = errorOf({candidate(0, "old", DeviceKind::DiscreteGpu, "no VK_KHR_push_descriptor")}, "");
    EXPECT_NE(error.find("no usable Vulkan device"), std::string::npos) << error;
    EXPECT_NE(error.find("#0 'old' discrete GPU"), std::string::npos) << error;
    EXPECT_NE(errorOf({}, "").find("available: none"), std::string::npos);
}

TEST(DeviceChoice, TheListMarksTheAutomaticChoiceAndUnusableDevices) {
    std::string list = describeDevices(machine());
    EXPECT_NE(list.find("#2  30313233-3435-3637-3839-3a3b3c3d3e3f  discrete GPU  NVIDIA GeForce RTX 4090  driver test, "
                        "Vulkan 1.3.0  (automatic choice)\n"),
              std::string::npos)
        << list;
    EXPECT_NE(list.find("(not usable: Vulkan 1.2.0, not 1.3)\n"), std::string::npos) << list;
    EXPECT_EQ(describeDevices({}), "no Vulkan device\n");
}

// The real devices (lavapipe in CI): the one the automatic choice makes is found again by its index, its UUID
// and its name, and each way opens the same device.
TEST(DeviceChoice, TheRealDeviceIsChosenByIndexUuidAndName) {
    std::vector<DeviceCandidate> devices = listDevices();
    ASSERT_FALSE(devices.empty());
    size_t chosen = chooseDevice(devices, "");
    const DeviceCandidate& c = devices[chosen];
    EXPECT_EQ(c.uuid.size(), 16u);
    for (const std::string& text :
         {"#" + std::to_string(c.index), std::to_string(c.index), formatDeviceUuid(c.uuid), c.name}) {
        Device device(DeviceOptions{.deviceFilter = text, .quiet = true});
        EXPECT_EQ(device.name(), c.name) << text;
        EXPECT_EQ(device.uuid(), formatDeviceUuid(c.uuid)) << text;
    }
}
