// The suite's correctness cross-check and the device record (render/bench_suite.h): the default frame rendered at
// the reference's settings, compared pixel by pixel with the reference files a lavapipe run wrote.
#include "render/bench_suite.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/staged_folder.h"
#include "dataset/frame_truth.h"
#include "engine/device.h"
#include "engine/device_choice.h"
#include "io/image_files.h"
#include "io/image_io.h"
#include "render/session.h"
#include "scene/scene_input.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>

namespace sward {

namespace {

namespace fs = std::filesystem;

constexpr const char* kReferenceFolder = "bench/reference";
constexpr const char* kReferenceImage = "reference.exr";
constexpr const char* kReferenceJson = "reference.json";
// The agreement bound: depth (and disparity) within a relative 1e-3 on at least 99.9 % of the pixels.
constexpr double kRelativeTolerance = 1e-3;
constexpr double kAgreeingFraction = 0.999;

// The planes the reference holds, as float32 EXR channels (instance ids < 2^24 and classes are exact in float).
struct CheckPlanes {
    uint32_t width = 0, height = 0;
    std::vector<float> depth, disparity, disparityRight, semantic, instance;
};
const std::vector<std::string>& planeNames() {
    static const std::vector<std::string> names = {"depth", "disparity", "disparity_right", "semantic", "instance"};
    return names;
}

std::string versionText(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

std::string uuidText(const uint8_t* bytes) {
    std::array<uint8_t, 16> uuid{};
    std::memcpy(uuid.data(), bytes, uuid.size());
    return formatDeviceUuid(uuid);
}

nlohmann::json settingsJson(const CrossCheckSettings& s) {
    return {{"scene", s.scene},
            {"resolution", std::to_string(s.width) + "x" + std::to_string(s.height)},
            {"samples", s.samples},
            {"baseline", s.baseline},
            {"frame", s.frame}};
}

// The default frame at the cross-check's settings through a Session (what sward-render writes for frame 0), as the
// dataset's files hold its truth (dataset/frame_truth.h). `deviceJson` receives the device it ran on.
CheckPlanes renderCheckFrame(const std::string& dataRoot, const std::string& device, nlohmann::json& deviceJson) {
    const CrossCheckSettings s;
    const nlohmann::json overrides = {
        {"render.resolution", {s.width, s.height}}, {"render.samples", s.samples}, {"camera.baseline", s.baseline}};
    Session session(loadSceneInput({.path = dataRoot + "/" + s.scene, .overrides = overrides.dump()}),
                    {.device = device});
    deviceJson = suiteDeviceJson(session.device());
    session.step(s.frame);
    const SessionFrame frame = session.render();
    const FrameTruth truth = frameTruth(frame.images, frame.cameras.left.fx, frame.baseline);
    CheckPlanes planes{.width = frame.images.width, .height = frame.images.height};
    planes.depth = frame.images.depth;
    planes.disparity = truth.disparity;
    planes.disparityRight = truth.rightDisparity;
    planes.semantic.assign(truth.semantic.begin(), truth.semantic.end());
    planes.instance = truth.instance;
    return planes;
}

std::vector<const std::vector<float>*> planeList(const CheckPlanes& p) {
    return {&p.depth, &p.disparity, &p.disparityRight, &p.semantic, &p.instance};
}

CheckPlanes readReference(const std::string& path) {
    CheckPlanes planes;
    std::vector<std::vector<float>*> targets = {&planes.depth, &planes.disparity, &planes.disparityRight,
                                                &planes.semantic, &planes.instance};
    for (size_t i = 0; i < targets.size(); ++i) {
        ImageData channel = loadExrChannel(path, planeNames()[i]);
        require(i == 0 || (channel.width == planes.width && channel.height == planes.height),
                "'" + path + "': its channels differ in size");
        planes.width = channel.width, planes.height = channel.height;
        *targets[i] = std::move(channel.samples);
    }
    return planes;
}

// Equal pixels (bitwise equal values; +inf sky equals +inf), pixels within the relative tolerance (both infinite,
// or |a - b| <= 1e-3 |reference|), and the largest relative difference among the finite pairs.
nlohmann::json compareValues(std::span<const float> measured, std::span<const float> reference) {
    uint64_t equal = 0, within = 0;
    double maxRelative = 0.0;
    for (size_t i = 0; i < reference.size(); ++i) {
        const float a = measured[i], b = reference[i];
        if (a == b || (std::isnan(a) && std::isnan(b))) {
            ++equal, ++within;
            continue;
        }
        if (!std::isfinite(a) || !std::isfinite(b)) continue;
        const double relative = std::fabs(double(a) - double(b)) / std::max(std::fabs(double(b)), 1e-30);
        maxRelative = std::max(maxRelative, relative);
        within += relative <= kRelativeTolerance;
    }
    const double n = double(std::max<size_t>(reference.size(), 1));
    return {{"equal_fraction", double(equal) / n},
            {"within_1e-3_fraction", double(within) / n},
            {"max_relative_difference", maxRelative}};
}

double equalFraction(std::span<const float> a, std::span<const float> b, std::span<const float> c,
                     std::span<const float> d) {
    uint64_t equal = 0;
    for (size_t i = 0; i < a.size(); ++i) equal += a[i] == b[i] && (c.empty() || c[i] == d[i]);
    return double(equal) / double(std::max<size_t>(a.size(), 1));
}

nlohmann::json readJsonFile(const std::string& path) {
    std::ifstream in(path);
    require(bool(in), "cannot read '" + path + "'");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error("'" + path + "' is not valid JSON: " + e.what());
    }
}

} // namespace

nlohmann::json suiteDeviceJson(const Device& device) {
    VkPhysicalDeviceVulkan12Properties v12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
    VkPhysicalDeviceVulkan11Properties v11{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES,
                                           .pNext = &v12};
    VkPhysicalDeviceProperties2 props2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &v11};
    vkGetPhysicalDeviceProperties2(device.physical(), &props2);
    const VkPhysicalDeviceProperties& p = device.properties();
    const VkPhysicalDeviceLimits& l = p.limits;
    nlohmann::json samples = nlohmann::json::array();
    for (uint32_t count = 1; count <= 64; count *= 2)
        if (l.framebufferColorSampleCounts & l.framebufferDepthSampleCounts & count) samples.push_back(count);
    nlohmann::json heaps = nlohmann::json::array();
    const VkPhysicalDeviceMemoryProperties& memory = device.memoryProperties();
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        heaps.push_back({{"bytes", memory.memoryHeaps[h].size},
                         {"device_local", (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0}});
    return {
        {"name", device.name()},
        {"driver", device.driver()},
        {"driver_name", v12.driverName},
        {"driver_info", v12.driverInfo},
        {"driver_version", p.driverVersion},
        {"vulkan_version", versionText(p.apiVersion)},
        {"vendor_id", p.vendorID},
        {"device_id", p.deviceID},
        {"type", deviceKindName(DeviceKind(p.deviceType))},
        {"uuid", uuidText(v11.deviceUUID)},
        {"driver_uuid", uuidText(v11.driverUUID)},
        {"limits",
         {{"max_image_dimension_2d", l.maxImageDimension2D},
          {"sample_counts", samples},
          {"subgroup_size", v11.subgroupSize},
          {"max_compute_workgroup_invocations", l.maxComputeWorkGroupInvocations},
          {"timestamp_period_ns", l.timestampPeriod},
          {"pipeline_statistics", device.supportsPipelineStatistics()},
          {"draw_indirect_count", device.supportsDrawIndirectCount()}}},
        {"memory_heaps", heaps},
    };
}

nlohmann::json suiteCrossCheck(const std::string& dataRoot, const std::string& device) {
    const std::string folder = dataRoot + "/" + kReferenceFolder;
    const nlohmann::json reference = readJsonFile(folder + "/" + kReferenceJson);
    const CheckPlanes expected = readReference(folder + "/" + kReferenceImage);
    const CrossCheckSettings s;
    require(reference.value("parameters", nlohmann::json()) == settingsJson(s),
            "'" + folder + "/" + kReferenceJson +
                "' was rendered with other settings than this build's cross-check "
                "(regenerate it: sward-bench suite --write-reference, docs/suite.md)");
    nlohmann::json deviceJson;
    const CheckPlanes measured = renderCheckFrame(dataRoot, device, deviceJson);
    require(measured.width == expected.width && measured.height == expected.height,
            "the cross-check frame is " + std::to_string(measured.width) + "x" + std::to_string(measured.height) +
                " but the reference is " + std::to_string(expected.width) + "x" + std::to_string(expected.height));
    nlohmann::json result = {
        {"parameters", settingsJson(s)},
        {"reference", {{"device", reference.at("device")}, {"driver", reference.at("driver")}}},
        {"device", deviceJson.at("name")},
        {"pixels", uint64_t(expected.width) * expected.height},
        {"depth", compareValues(measured.depth, expected.depth)},
        {"disparity", compareValues(measured.disparity, expected.disparity)},
        {"disparity_right", compareValues(measured.disparityRight, expected.disparityRight)},
        {"labels",
         {{"equal_fraction",
           equalFraction(measured.semantic, expected.semantic, measured.instance, expected.instance)}}},
        {"semantic", {{"equal_fraction", equalFraction(measured.semantic, expected.semantic, {}, {})}}},
    };
    bool agrees = true, exact = true;
    for (const char* key : {"depth", "disparity", "disparity_right"}) {
        agrees = agrees && result[key]["within_1e-3_fraction"].get<double>() >= kAgreeingFraction;
        exact = exact && result[key]["equal_fraction"].get<double>() == 1.0;
    }
    result["agrees"] = agrees;
    result["exact"] = exact && result["labels"]["equal_fraction"].get<double>() == 1.0;
    return result;
}

nlohmann::json writeSuiteReference(const std::string& outDir, bool overwrite, const std::string& dataRoot,
                                   const std::string& device) {
    std::error_code ec;
    require(overwrite || !fs::is_directory(outDir, ec) || fs::is_empty(outDir, ec),
            "--write-reference: '" + outDir + "' is not empty; use --overwrite to replace its reference files");
    StagedFolder folder(outDir, "reference folder");
    nlohmann::json deviceJson;
    const CheckPlanes planes = renderCheckFrame(dataRoot, device, deviceJson);
    std::vector<std::span<const float>> spans;
    for (const std::vector<float>* plane : planeList(planes)) spans.emplace_back(*plane);
    writeExrFloatChannels(folder.path() + "/" + kReferenceImage, planes.width, planes.height, planeNames(), spans);
    const nlohmann::json reference = {
        {"format", "sward-suite-reference-1"},
        {"parameters", settingsJson(CrossCheckSettings{})},
        {"channels", planeNames()},
        {"device", deviceJson.at("name")},
        {"driver", deviceJson.at("driver")},
        {"vulkan_version", deviceJson.at("vulkan_version")},
        {"regenerate", "sward-bench suite --write-reference bench/reference --overwrite --device llvmpipe"},
    };
    writeTextAtomically(folder.path() + "/" + kReferenceJson, reference.dump(2) + "\n");
    folder.commit();
    return reference;
}

} // namespace sward
