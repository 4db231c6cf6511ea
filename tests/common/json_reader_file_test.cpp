// The one JSON loading function: duplicate keys, invalid JSON, nesting and size limits, each one clear error.
#include "common/error.h"
#include "common/json_reader.h"
#include "common/stopwatch.h"

#include "sanitized_build.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>

using namespace sward;
using sward::test::errorOf;

namespace {
#if defined(NDEBUG) && !defined(SWARD_TEST_SANITIZED)
constexpr bool kTimedBuild = true;
#else
constexpr bool kTimedBuild = false;
#endif

std::string parseError(const std::string& text) {
    return errorOf([&] { parseJsonText(text, "s.json", "scene file"); });
}
} // namespace

TEST(JsonFile, DuplicateKeysAreRefusedNamingTheirJsonPath) {
    EXPECT_EQ(parseError(R"({"wind": {"strength": 0.1, "strength": 0.2}})"), "s.json: 'wind.strength' appears twice");
    EXPECT_EQ(parseError(R"({"seed": 1, "seed": 1})"), "s.json: 'seed' appears twice");
    EXPECT_EQ(parseError(R"({"objects": [{"name": "a"}, {"model": "m", "path": {"points": [], "points": []}}]})"),
              "s.json: 'objects[1].path.points' appears twice");
    EXPECT_EQ(parseError(R"({"a": [[1, 2], [{"k": 1}, 3, {"k": 1, "k": 2}]]})"), "s.json: 'a[1][2].k' appears twice");
}

TEST(JsonFile, TheSameKeyInDifferentObjectsIsFine) {
    const nlohmann::json json =
        parseJsonText(R"({"a": {"k": 1}, "b": {"k": 2}, "l": [{"k": 3}, {"k": 4}], "k": 5})", "s.json", "scene file");
    EXPECT_EQ(json["l"][1]["k"], 4);
    EXPECT_EQ(json["k"], 5);
}

TEST(JsonFile, ANumberBeyondADoubleNamesItsKey) {
    EXPECT_EQ(parseError(R"({"camera": {"fov_y_deg": 1e400}})"),
              "s.json: 'camera.fov_y_deg' is outside the range of a double");
    EXPECT_EQ(parseError(R"({"points": [[1, 2], [3, -1e999]]})"),
              "s.json: 'points[1][1]' is outside the range of a double");
    EXPECT_EQ(parseError("1e400"), "s.json: a number is outside the range of a double");
}

TEST(JsonFile, InvalidJsonNamesTheLineAndColumnWithoutLibraryText) {
    EXPECT_EQ(parseError("{\n  \"a\": 1,\n  x\n}"), "s.json: the scene file is not valid JSON (line 3, column 3)");
    EXPECT_EQ(parseError(""), "s.json: the scene file is not valid JSON (line 1, column 1)");
}

TEST(JsonFile, DeepNestingIsRefused) {
    const std::string ok = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
    EXPECT_NO_THROW(parseJsonText(ok, "s.json", "scene file"));
    const std::string deep = std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']');
    EXPECT_EQ(parseError(deep), "s.json: JSON nested deeper than 64 levels");
}

TEST(JsonFile, FilesAreReadWithTheSameChecks) {
    const auto dir = test::tempDir();
    const std::string path = (dir / "scene.json").string();
    std::ofstream(path) << R"({"name": "x", "name": "y"})";
    EXPECT_EQ(errorOf([&] { readJsonFile(path, "scene file"); }), path + ": 'name' appears twice");
    std::ofstream(path) << R"({"name": "x"})";
    EXPECT_EQ(readJsonFile(path, "scene file")["name"], "x");
    const std::string missing = (dir / "missing.json").string();
    EXPECT_EQ(errorOf([&] { readJsonFile(missing, "scene file"); }),
              missing + ": cannot open the scene file (missing or unreadable)");
}

TEST(JsonFile, AFileOverTheSizeLimitIsRefusedBeforeItIsRead) {
    const auto dir = test::tempDir();
    const std::string path = (dir / "huge.json").string();
    { std::ofstream(path) << "{}"; }
    // A sparse file: the size check must refuse it from its length, without reading 64 MiB.
    std::filesystem::resize_file(path, kMaxJsonFileBytes + 1);
    EXPECT_EQ(errorOf([&] { readJsonFile(path, "scene file"); }),
              path + ": the scene file has 67108865 bytes, over the limit of 64 MiB");
}

namespace {

// {"colliders": [{"r":1}, ... `items` times]}, parsed; returns the parse's process CPU time in ms (CPU, not wall:
// the test machines are shared, and another process's load must not look like a slower parser).
double cpuMsToParseItems(size_t items) {
    std::string text = "{\"colliders\": [";
    text.reserve(items * 8 + 32);
    for (size_t i = 0; i < items; ++i) text += i ? ",{\"r\":1}" : "{\"r\":1}";
    text += "]}";
    const Stopwatch clock = Stopwatch::withCpuTime();
    const nlohmann::json json = parseJsonText(text, "s.json", "scene file");
    const double ms = clock.cpuMs();
    EXPECT_EQ(json["colliders"].size(), items);
    EXPECT_EQ(json["colliders"][items - 1]["r"], 1);
    return ms;
}

} // namespace

// nlohmann's callback parser rescanned the whole enclosing array after every object in it (O(n^2): 200,000
// colliders took 20.7 s, 10^6 gave no answer in 120 s); the checked builder is linear. Checked as a ratio in one
// run: 8x the items must cost well under 8^2 = 64x the time (linear is 8x; 24x leaves room for noise and caches).
TEST(JsonFile, AMillionArrayItemsParseInLinearTime) {
    constexpr size_t kItems = 1000000;
    const double small = std::max(cpuMsToParseItems(kItems / 8), 1.0);
    const double large = cpuMsToParseItems(kItems);
    EXPECT_LT(large, 24.0 * small) << "10^6 items: " << large << " ms of CPU, 125,000: " << small << " ms";
    // The issue's figure (under 2 s for 10^6 items), in an optimised build without sanitizers only (they are
    // several times slower); the parses above run everywhere.
    if (kTimedBuild) {
        EXPECT_LT(large, 2000.0) << "parsing 10^6 array items took " << large << " ms of CPU";
    }
}

TEST(JsonFile, ADuplicateKeyDeepInALongArrayIsNamedByItsIndex) {
    std::string text = "[";
    for (int i = 0; i < 1000; ++i) text += R"({"k": 1},)";
    text += R"({"a": [1, {"k": 1, "k": 2}]}])";
    EXPECT_EQ(parseError(text), "s.json: '[1000].a[1].k' appears twice");
}
