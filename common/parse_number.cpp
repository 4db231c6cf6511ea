#include "common/parse_number.h"

#include "common/error.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace sward {

namespace {

std::string quoted(std::string_view text) {
    return "'" + std::string(text) + "'";
}

// Shortest text of a bound: "170", "0.5", "1e+308".
std::string boundText(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

} // namespace

uint64_t parseUnsigned(std::string_view text, uint64_t min, uint64_t max, std::string_view what) {
    const std::string expected = std::string(what) + " must be a whole number from " + std::to_string(min) + " to " +
                                 std::to_string(max) + ", got " + quoted(text);
    // from_chars alone would accept a leading '-' for signed types only, but checking digits first also refuses
    // "+5", " 5" and "" with the same message.
    require(!text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos, expected);
    uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    require(error == std::errc() && end == text.data() + text.size() && value >= min && value <= max, expected);
    return value;
}

int64_t parseInteger(std::string_view text, int64_t min, int64_t max, std::string_view what) {
    const std::string expected = std::string(what) + " must be a whole number from " + std::to_string(min) + " to " +
                                 std::to_string(max) + ", got " + quoted(text);
    const bool negative = text.starts_with('-');
    const std::string_view digits = negative ? text.substr(1) : text;
    require(!digits.empty() && digits.find_first_not_of("0123456789") == std::string_view::npos, expected);
    int64_t value = 0;
    // from_chars for int64_t takes the '-' itself and reports overflow, so INT64_MIN parses exactly.
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    require(error == std::errc() && end == text.data() + text.size() && value >= min && value <= max, expected);
    return value;
}

double parseReal(std::string_view text, double min, double max, std::string_view what) {
    const std::string expected = std::string(what) + " must be a number from " + boundText(min) + " to " +
                                 boundText(max) + ", got " + quoted(text);
    // from_chars for double takes no leading '+' and no hex without the format flag: only decimal text passes.
    require(!text.empty() && text.find_first_not_of("0123456789+-.eE") == std::string_view::npos, expected);
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    require(error == std::errc() && end == text.data() + text.size() && std::isfinite(value) && value >= min &&
                value <= max,
            expected);
    return value;
}

std::pair<std::string_view, std::string_view> splitPair(std::string_view text, char separator, std::string_view what,
                                                        std::string_view form) {
    const size_t at = text.find(separator);
    require(at != std::string_view::npos && text.find(separator, at + 1) == std::string_view::npos,
            std::string(what) + " must be " + std::string(form) + ", got " + quoted(text));
    return {text.substr(0, at), text.substr(at + 1)};
}

std::pair<uint64_t, uint64_t> parseHalfOpenRange(std::string_view text, uint64_t min, uint64_t max,
                                                 std::string_view what) {
    const std::string range = std::string(what) + " " + quoted(text);
    const auto [first, end] = splitPair(text, ':', what, "A:B (items A .. B-1)");
    const uint64_t a = parseUnsigned(first, min, max - 1, range + ": start");
    const uint64_t b = parseUnsigned(end, min + 1, max, range + ": end");
    require(a < b, range + ": start must be less than end (A:B covers A .. B-1)");
    return {a, b};
}

} // namespace sward
