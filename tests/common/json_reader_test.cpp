// The one JSON reader: typed, range-checked values, unknown keys rejected, errors naming file and JSON path.
#include "common/error.h"
#include "common/json_reader.h"

#include <gtest/gtest.h>

#include <functional>

using namespace sward;

namespace {
std::string errorOf(const std::function<void()>& read) {
    try {
        read();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
} // namespace

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
    EXPECT_EQ(errorOf([&] { JsonReader(nlohmann::json::array(), "f.json"); }), "f.json: the file must hold a JSON object");
}
