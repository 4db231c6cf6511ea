// The one JSON reader: typed, range-checked values, unknown keys rejected, errors naming file and JSON path.
#include "common/error.h"
#include "common/json_reader.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <functional>

using namespace sward;
using sward::test::errorOf;

TEST(JsonReader, ReadsValuesAndKeepsDefaultsForAbsentKeys) {
    const auto json = nlohmann::json::parse(R"({"a": 0.5, "n": 18446744073709551615, "s": "x", "b": true})");
    JsonReader r(json, "f.json");
    EXPECT_EQ(r.number("a", 0.0, 0.0, 1.0), 0.5);
    EXPECT_EQ(r.integer("n", 0, 0, UINT64_MAX), UINT64_MAX) << "exact, not rounded through a double";
    EXPECT_EQ(r.string("s", ""), "x");
    EXPECT_TRUE(r.boolean("b", false));
    EXPECT_EQ(r.number("absent", 7.0, 0.0, 10.0), 7.0);
    EXPECT_NO_THROW(r.finish());
}

TEST(JsonReader, ErrorsNameTheFileAndTheJsonPath) {
    const auto json = nlohmann::json::parse(R"({"o": {"list": [{"k": 2}, {"k": "no"}]}, "typo": 1})");
    EXPECT_EQ(errorOf([&] {
                  JsonReader r(json, "f.json");
                  auto items = r.child("o").objects("list");
                  items[1].number("k", 0.0, 0.0, 5.0);
              }),
              "f.json: 'o.list[1].k' must be a number");
    EXPECT_EQ(errorOf([&] {
                  JsonReader r(json, "f.json");
                  r.child("o").objects("list")[0].number("k", 0.0, 0.0, 1.0);
              }),
              "f.json: 'o.list[0].k' must be between 0 and 1 (got 2)");
    EXPECT_EQ(errorOf([&] {
                  JsonReader r(json, "f.json");
                  r.raw("o");
                  r.finish();
              }),
              "f.json: unknown key 'typo'");
    EXPECT_EQ(errorOf([&] { JsonReader(nlohmann::json::array(), "f.json"); }),
              "f.json: the file must hold a JSON object");
}

TEST(JsonReader, ChoiceReturnsTheIndexOfANamedValue) {
    const auto json = nlohmann::json::parse(R"({"shape": "box", "bad": "cone", "number": 3})");
    JsonReader r(json, "f.json");
    EXPECT_EQ(r.choice("shape", 0, {"sphere", "capsule", "box"}), 2);
    EXPECT_EQ(r.choice("absent", 1, {"sphere", "capsule", "box"}), 1);
    EXPECT_EQ(errorOf([&] {
                  r.choice("bad", 0, {"sphere", "capsule", "box"});
              }),
              "f.json: 'bad' must be sphere, capsule or box");
    EXPECT_EQ(errorOf([&] { r.choice("number", 0, {"x", "y"}); }), "f.json: 'number' must be x or y");
}

TEST(JsonReader, RequiredKeysNameWhatIsMissing) {
    const auto json = nlohmann::json::parse(R"({"o": {"path": {"speed": 1}}})");
    JsonReader r(json, "f.json");
    JsonReader o = r.child("o");
    EXPECT_EQ(o.required("path", "a path").at("speed"), 1);
    EXPECT_EQ(o.childPath("path"), "o.path");
    EXPECT_EQ(errorOf([&] { o.required("model", "a .gltf file"); }), "f.json: 'o.model' is required (a .gltf file)");
}

TEST(JsonReader, WholeVectorsRejectFractionsAndOutOfRangeValues) {
    const auto json = nlohmann::json::parse(R"({"size": [640, 480.0], "half": [640.5, 480], "big": [0, 20000]})");
    JsonReader r(json, "f.json");
    EXPECT_EQ(r.wholeVector<2>("size", glm::uvec2(1), 1, 16384), glm::uvec2(640, 480));
    EXPECT_EQ(r.wholeVector<2>("absent", glm::uvec2(7, 8), 1, 16384), glm::uvec2(7, 8));
    EXPECT_EQ(errorOf([&] { r.wholeVector<2>("half", glm::uvec2(1), 1, 16384); }),
              "f.json: 'half' must hold whole numbers");
    EXPECT_EQ(errorOf([&] { r.wholeVector<2>("big", glm::uvec2(1), 1, 16384); }),
              "f.json: 'big' must hold numbers between 1 and 16384");
}

TEST(JsonReader, ArraysOfVectorsAreReadElementByElement) {
    const auto json = nlohmann::json::parse(R"({"points": [[0, 1], [2.5, -3]], "flat": [0, 1], "far": [[0, 1e9]]})");
    JsonReader r(json, "f.json");
    const auto points = r.vectors<2>("points", -100.0, 100.0);
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[1], glm::dvec2(2.5, -3.0));
    EXPECT_TRUE(r.vectors<2>("absent", -100.0, 100.0).empty());
    EXPECT_EQ(errorOf([&] { r.vectors<2>("flat", -100.0, 100.0); }),
              "f.json: 'flat' must be an array of arrays of 2 numbers between -100 and 100");
    EXPECT_EQ(errorOf([&] { r.vectors<2>("far", -100.0, 100.0); }),
              "f.json: 'far' must be an array of arrays of 2 numbers between -100 and 100");
}

TEST(JsonReader, IntegersOutsideTheRangeOrTheTypeAreRefusedNeverWrapped) {
    const auto json = nlohmann::json::parse(R"({"wrap32": 4294967296, "wrap64": 18446744073709551616, "neg": -1,
        "half": 2.5, "text": "3", "big": 1e308, "ok": 4294967295})");
    JsonReader r(json, "s.json", "sequence");
    const auto error = [&](const char* key) { return errorOf([&] { r.integer(key, 1, 1, 1000000); }); };
    EXPECT_EQ(error("wrap32"), "s.json: 'sequence.wrap32' must be an integer in [1, 1000000] (got 4294967296)");
    EXPECT_EQ(error("wrap64"),
              "s.json: 'sequence.wrap64' must be an integer in [1, 1000000] (got 1.8446744073709552e+19)");
    EXPECT_EQ(error("neg"), "s.json: 'sequence.neg' must be an integer in [1, 1000000] (got -1)");
    EXPECT_EQ(error("half"), "s.json: 'sequence.half' must be an integer in [1, 1000000] (got 2.5)");
    EXPECT_EQ(error("text"), "s.json: 'sequence.text' must be an integer in [1, 1000000] (got a string)");
    EXPECT_EQ(error("big"), "s.json: 'sequence.big' must be an integer in [1, 1000000] (got 1e+308)");
    EXPECT_EQ(r.integer("ok", 0, 0, UINT32_MAX), 4294967295u);
    EXPECT_EQ(errorOf([&] { r.integer("wrap64", 0, 0, UINT64_MAX); }),
              "s.json: 'sequence.wrap64' must be an integer in [0, 18446744073709551615] (got 1.8446744073709552e+19)");
}

TEST(JsonReader, FloatValuesStayFinite) {
    const auto json = nlohmann::json::parse(R"({"huge": 1e308, "x": 2})");
    JsonReader r(json, "s.json");
    EXPECT_EQ(r.numberF("x", 0.0f, 0.0f, 10.0f), 2.0f);
    EXPECT_EQ(errorOf([&] { r.numberF("huge", 0.0f, 0.0f, 1e6f); }),
              "s.json: 'huge' must be between 0 and 1e+06 (got 1e+308)");
}
