// sward-bench suite: every headline figure of docs/benchmarks.md in one bounded run, on whatever GPU the machine has,
// with a correctness cross-check against reference images rendered by lavapipe (docs/suite.md). It runs the
// benchmarks of render/benchmarks.h and range/range_benchmark.h with fixed parameters (a full and a --quick set),
// records each figure's parameters beside its result, and writes suite.json (docs/suite.schema.json) and suite.md.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

class Device;

// The format name suite.json carries; a new major number when a field changes meaning.
inline constexpr const char* kSuiteFormat = "sward-suite-1";

struct SuiteOptions {
    std::string outDir;            // suite.json and suite.md go here (refused when not empty, unless overwrite)
    bool overwrite = false;        // replace suite.json / suite.md in a non-empty outDir
    bool quick = false;            // smaller sizes and fewer frames: < 3 minutes on lavapipe with 2 cores
    std::string device;            // Vulkan device selection, passed through unchanged to every benchmark
    std::string dataRoot;          // the folder holding examples/ and bench/reference/; empty: suiteDataRoot()
    std::vector<std::string> only; // figure names (suiteFigureNames) to run; the others are recorded as skipped
};

// The suite's figures, in the order they run and appear in suite.json and suite.md.
const std::vector<std::string>& suiteFigureNames();

// Where the examples and the reference live: <executable>/../share/sward of an installed tree or unpacked release when
// it holds examples/meadow.json, else this source tree.
std::string suiteDataRoot();

// Checks the options and the output folder (before any work), runs every selected figure, and writes suite.json and
// suite.md atomically through a staged folder. A figure that throws is recorded as failed with its message, and the
// others still run. Returns the suite's JSON.
nlohmann::json runBenchSuite(const SuiteOptions& options);

// suite.md: the device, then one row per figure (its parameters and headline numbers), then the cross-check.
std::string suiteTable(const nlohmann::json& suite);

// True when every selected figure was measured and the cross-check (when run) agreed: the tool's exit status.
bool suitePassed(const nlohmann::json& suite);

// The device as suite.json records it: name, driver, Vulkan version, UUIDs, type, the limits sward queries, heaps.
nlohmann::json suiteDeviceJson(const Device& device);

// The cross-check's render settings (both modes): the default scene at a small size, as a stereo rig.
struct CrossCheckSettings {
    std::string scene = "examples/meadow.json"; // relative to the data root
    uint32_t width = 320, height = 240, samples = 1;
    double baseline = 0.12; // metres: the rig gives the default frame a disparity (the example is mono)
    uint32_t frame = 0;
};

// Renders the cross-check frame on `device` and compares its depth, disparity (both views) and labels with the
// reference in <dataRoot>/bench/reference/. Keys: parameters, reference (its device and driver), pixels, depth /
// disparity / disparity_right (equal_fraction, within_1e-3_fraction, max_relative_difference), labels and semantic
// (equal_fraction), agrees (depth and both disparities within relative 1e-3 on >= 99.9 % of pixels), exact (every
// equal_fraction 1).
nlohmann::json suiteCrossCheck(const std::string& dataRoot, const std::string& device);

// Renders the cross-check frame on `device` and writes the reference (reference.exr, reference.json) into outDir
// through a staged folder; refuses a non-empty outDir unless overwrite. Returns reference.json's content.
nlohmann::json writeSuiteReference(const std::string& outDir, bool overwrite, const std::string& dataRoot,
                                   const std::string& device);

} // namespace sward
