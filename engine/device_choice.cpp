#include "engine/device_choice.h"

#include "common/error.h"

#include <algorithm>
#include <cctype>

namespace sward {

namespace {

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

int kindRank(DeviceKind kind) {
    switch (kind) {
    case DeviceKind::DiscreteGpu:
        return 4;
    case DeviceKind::IntegratedGpu:
        return 3;
    case DeviceKind::VirtualGpu:
        return 2;
    case DeviceKind::Cpu:
        return 1;
    default:
        return 0;
    }
}

bool isDigits(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool isUuidText(const std::string& s) {
    if (s.size() != 36) return false;
    for (size_t i = 0; i < s.size(); ++i) {
        bool dash = i == 8 || i == 13 || i == 18 || i == 23;
        if (dash ? s[i] != '-' : !std::isxdigit(static_cast<unsigned char>(s[i]))) return false;
    }
    return true;
}

std::string label(const DeviceCandidate& c) {
    return "#" + std::to_string(c.index) + " '" + c.name + "'";
}

std::string listing(const std::vector<DeviceCandidate>& candidates) {
    std::string out;
    for (const DeviceCandidate& c : candidates)
        out += (out.empty() ? "" : ", ") + label(c) + " " + deviceKindName(c.kind) + " " + formatDeviceUuid(c.uuid) +
               (c.unusable.empty() ? "" : " (not usable: " + c.unusable + ")");
    return "available: " + (out.empty() ? std::string("none") : out);
}

// The usable device of the best kind among `matches`, the first of equals when `firstOfEquals`, else an error
// naming the tied ones.
size_t bestOf(const std::vector<DeviceCandidate>& candidates, const std::vector<size_t>& matches, bool firstOfEquals,
              const std::string& text) {
    int best = -1;
    std::vector<size_t> tied;
    for (size_t i : matches) {
        if (!candidates[i].unusable.empty()) continue;
        int rank = kindRank(candidates[i].kind);
        if (rank < best) continue;
        if (rank > best) tied.clear();
        tied.push_back(i);
        best = rank;
    }
    if (tied.size() == 1 || (firstOfEquals && !tied.empty())) return tied.front();
    if (tied.empty()) {
        std::string why = text.empty() ? "no usable Vulkan device (sward needs Vulkan 1.3, a graphics + compute queue "
                                         "and VK_KHR_push_descriptor)"
                                       : "every Vulkan device matching '" + text + "' is unusable";
        if (!text.empty() && matches.empty()) why = "no Vulkan device matches '" + text + "'";
        throw Error(why + " (" + listing(candidates) + ")");
    }
    std::string names;
    for (size_t i : tied) names += (names.empty() ? "" : ", ") + label(candidates[i]);
    throw Error("--device '" + text + "' matches " + std::to_string(tied.size()) + " devices of the same type (" +
                names + "): choose one by index (#N) or UUID (" + listing(candidates) + ")");
}

// An index or UUID names one device: it must exist and be usable.
size_t exactly(const std::vector<DeviceCandidate>& candidates, const std::vector<size_t>& matches,
               const std::string& text) {
    if (matches.empty()) throw Error("no Vulkan device matches '" + text + "' (" + listing(candidates) + ")");
    // One driver enumerated twice (two ICD files of lavapipe) gives two devices of one UUID: only an index tells.
    if (matches.size() > 1)
        throw Error("--device '" + text + "' is the UUID of " + std::to_string(matches.size()) +
                    " devices: choose one by index (#N) (" + listing(candidates) + ")");
    const DeviceCandidate& c = candidates[matches.front()];
    if (!c.unusable.empty())
        throw Error("Vulkan device " + label(c) + " is not usable: " + c.unusable + " (" + listing(candidates) + ")");
    return matches.front();
}

} // namespace

std::string formatDeviceUuid(const std::array<uint8_t, 16>& uuid) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (size_t i = 0; i < uuid.size(); ++i) {
        if (i == 4 || i == 6 || i == 8 || i == 10) out += '-';
        out += hex[uuid[i] >> 4];
        out += hex[uuid[i] & 15];
    }
    return out;
}

const char* deviceKindName(DeviceKind kind) {
    switch (kind) {
    case DeviceKind::DiscreteGpu:
        return "discrete GPU";
    case DeviceKind::IntegratedGpu:
        return "integrated GPU";
    case DeviceKind::VirtualGpu:
        return "virtual GPU";
    case DeviceKind::Cpu:
        return "CPU";
    default:
        return "other";
    }
}

size_t chooseDevice(const std::vector<DeviceCandidate>& candidates, const std::string& text) {
    std::vector<size_t> matches;
    if (text.empty()) {
        for (size_t i = 0; i < candidates.size(); ++i) matches.push_back(i);
        return bestOf(candidates, matches, true, text);
    }
    std::string number = text[0] == '#' ? text.substr(1) : text;
    if (isDigits(number)) {
        for (size_t i = 0; i < candidates.size(); ++i)
            if (number.size() <= 9 && candidates[i].index == std::stoul(number)) matches.push_back(i);
        return exactly(candidates, matches, text);
    }
    require(text[0] != '#', "--device '" + text + "': '#' must be followed by a device index, e.g. #0");
    if (isUuidText(text)) {
        for (size_t i = 0; i < candidates.size(); ++i)
            if (formatDeviceUuid(candidates[i].uuid) == lowercase(text)) matches.push_back(i);
        return exactly(candidates, matches, text);
    }
    for (size_t i = 0; i < candidates.size(); ++i)
        if (lowercase(candidates[i].name) == lowercase(text)) matches.push_back(i);
    if (matches.empty())
        for (size_t i = 0; i < candidates.size(); ++i)
            if (lowercase(candidates[i].name).find(lowercase(text)) != std::string::npos) matches.push_back(i);
    return bestOf(candidates, matches, false, text);
}

std::string describeDevices(const std::vector<DeviceCandidate>& candidates) {
    size_t automatic = candidates.size();
    try {
        automatic = chooseDevice(candidates, "");
    } catch (const Error&) {
    }
    std::string out;
    for (size_t i = 0; i < candidates.size(); ++i) {
        const DeviceCandidate& c = candidates[i];
        out += "#" + std::to_string(c.index) + "  " + formatDeviceUuid(c.uuid) + "  " + deviceKindName(c.kind) + "  " +
               c.name + "  driver " + c.driver + ", Vulkan " + c.apiVersion +
               (c.unusable.empty() ? "" : "  (not usable: " + c.unusable + ")") +
               (i == automatic ? "  (automatic choice)" : "") + "\n";
    }
    return out.empty() ? "no Vulkan device\n" : out;
}

} // namespace sward
