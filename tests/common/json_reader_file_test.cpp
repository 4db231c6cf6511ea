// The one JSON loading function: duplicate keys, invalid JSON, nesting and size limits, each one clear error.
#include "common/error.h"
#include "common/json_reader.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

using namespace sward;
using sward::test::errorOf;

namespace {
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
    const nlohmann::json json = parseJsonText(R"({"a": {"k": 1}, "b": {"k": 2}, "l": [{"k": 3}, {"k": 4}], "k": 5})",
                                              "s.json", "scene file");
    EXPECT_EQ(json["l"][1]["k"], 4);
    EXPECT_EQ(json["k"], 5);
}

TEST(JsonFile, ANumberBeyondADoubleNamesItsKey) {
    EXPECT_EQ(parseError(R"({"camera": {"fov_y_deg": 1e400}})"),
              "s.json: 'camera.fov_y_deg' is outside the range of a double");
    EXPECT_EQ(parseError(R"({"points": [[1, 2], [3, -1e999]]})"), "s.json: 'points[1][1]' is outside the range of a double");
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
