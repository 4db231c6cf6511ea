#include "common/json_reader.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace sward {

namespace {

// Tracks the JSON path of the parser's position so that a duplicate key can be named ("rows[2].cells"). The
// DOM parser would silently keep the last value of a repeated key; a scene that says "strength" twice is a
// mistake, and which value wins must not be an accident of the library.
class DuplicateKeyCheck {
public:
    explicit DuplicateKeyCheck(const std::string& source) : source_(source) {}

    bool operator()(int depth, nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
        case Event::object_start:
        case Event::array_start:
            if (uint32_t(depth) >= kMaxJsonDepth)
                throw Error(source_ + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
            frames_.push_back({elementPath(), event == Event::array_start, 0, {}, {}});
            break;
        case Event::key: {
            Frame& top = frames_.back();
            top.lastKey = parsed.get<std::string>();
            if (!top.keys.insert(top.lastKey).second)
                throw Error(source_ + ": '" + join(top.path, top.lastKey) + "' appears twice");
            break;
        }
        case Event::value:
            elementPath(); // counts the element when the value is an array element
            break;
        case Event::object_end:
        case Event::array_end:
            frames_.pop_back();
            break;
        }
        return true;
    }

private:
    struct Frame {
        std::string path;
        bool array;
        size_t next; // index of the next element of an array
        std::string lastKey;
        std::set<std::string> keys;
    };

    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }
    // The path of the element that starts now (an array's next element or the value of the last key).
    std::string elementPath() {
        if (frames_.empty()) return "";
        Frame& top = frames_.back();
        if (top.array) return top.path + "[" + std::to_string(top.next++) + "]";
        return join(top.path, top.lastKey);
    }

public:
    // The path of the value being read when the parser stopped (a number too large for a double, say).
    std::string pendingPath() const {
        if (frames_.empty()) return "";
        const Frame& top = frames_.back();
        if (top.array) return top.path + "[" + std::to_string(top.next) + "]";
        return join(top.path, top.lastKey);
    }

private:
    const std::string& source_;
    std::vector<Frame> frames_;
};

// A value as an error message quotes it: numbers, booleans and null as written, long things by their kind.
std::string shortDescription(const nlohmann::json& v) {
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return v.dump();
}

} // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& source, const std::string& what) {
    if (text.size() > kMaxJsonFileBytes)
        throw Error(source + ": the " + what + " has " + std::to_string(text.size()) + " bytes, over the limit of " +
                    std::to_string(kMaxJsonFileBytes >> 20) + " MiB");
    DuplicateKeyCheck check(source);
    try {
        return nlohmann::json::parse(text.begin(), text.end(), std::ref(check));
    } catch (const nlohmann::json::out_of_range&) {
        // 1e400 and the like: the library names only the number; the key tells the user where it is.
        const std::string path = check.pendingPath();
        throw Error(source + ": " + (path.empty() ? "a number" : "'" + path + "'") +
                    " is outside the range of a double");
    } catch (const nlohmann::json::parse_error& e) {
        // The library's message quotes the bytes it read; the position is all a user needs to find the mistake.
        const size_t at = std::min<size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
        const std::string_view before = text.substr(0, at);
        const size_t line = size_t(std::count(before.begin(), before.end(), '\n')) + 1;
        const size_t lineStart = before.rfind('\n');
        const size_t column = at - (lineStart == std::string_view::npos ? 0 : lineStart + 1) + 1;
        throw Error(source + ": the " + what + " is not valid JSON (line " + std::to_string(line) + ", column " +
                    std::to_string(column) + ")");
    }
}

nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    std::ifstream file(path, std::ios::binary);
    if (ec || !file) throw Error(path + ": cannot open the " + what + " (missing or unreadable)");
    // Checked before reading, so a huge file is refused without being loaded.
    if (size > kMaxJsonFileBytes)
        throw Error(path + ": the " + what + " has " + std::to_string(size) + " bytes, over the limit of " +
                    std::to_string(kMaxJsonFileBytes >> 20) + " MiB");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw Error(path + ": cannot read the " + what);
    return parseJsonText(text.str(), path, what);
}

JsonReader::JsonReader(const nlohmann::json& json, std::string source, std::string path)
    : json_(json), source_(std::move(source)), path_(std::move(path)) {
    if (!json_.is_object()) fail(path_.empty() ? "the file must hold a JSON object" : "'" + path_ + "' must be an object");
}

double JsonReader::number(const char* key, double value, double lo, double hi) {
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_number()) fail(name(key) + " must be a number");
        value = v->get<double>();
        if (!std::isfinite(value) || value < lo || value > hi)
            fail(name(key) + " must be between " + formatNumber(lo) + " and " + formatNumber(hi) + " (got " +
                 formatNumber(value) + ")");
    }
    return value;
}

float JsonReader::numberF(const char* key, float value, float lo, float hi) {
    // A bound beyond the float range would let a value through that becomes inf when stored.
    if (!std::isfinite(lo) || !std::isfinite(hi)) fail(name(key) + ": range not representable as a float");
    return float(number(key, value, lo, hi));
}

uint64_t JsonReader::integer(const char* key, uint64_t value, uint64_t lo, uint64_t hi) {
    if (const nlohmann::json* v = find(key)) {
        // Values beyond 2^64 - 1 arrive as doubles and negative ones as signed: both are refused, never wrapped.
        const bool whole = v->is_number_unsigned() || (v->is_number_integer() && v->get<int64_t>() >= 0);
        if (!whole || v->get<uint64_t>() < lo || v->get<uint64_t>() > hi)
            fail(name(key) + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                 shortDescription(*v) + ")");
        value = v->get<uint64_t>();
    }
    return value;
}

std::string JsonReader::string(const char* key, std::string value) {
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_string()) fail(name(key) + " must be a string");
        value = v->get<std::string>();
    }
    return value;
}

std::vector<std::string> JsonReader::strings(const char* key, size_t maxCount) {
    std::vector<std::string> values;
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_array()) fail(name(key) + " must be an array of strings");
        if (v->size() > maxCount)
            fail(name(key) + " has " + std::to_string(v->size()) + " entries, over the limit of " +
                 std::to_string(maxCount));
        for (const nlohmann::json& s : *v) {
            if (!s.is_string()) fail(name(key) + " must be an array of strings");
            values.push_back(s.get<std::string>());
        }
    }
    return values;
}

bool JsonReader::boolean(const char* key, bool value) {
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_boolean()) fail(name(key) + " must be true or false");
        value = v->get<bool>();
    }
    return value;
}

int JsonReader::choice(const char* key, int value, std::initializer_list<const char*> names) {
    if (const nlohmann::json* v = find(key)) {
        std::string list;
        int index = 0, found = -1;
        for (const char* n : names) {
            if (v->is_string() && v->get<std::string>() == n) found = index;
            list += (index ? (index + 1 == int(names.size()) ? " or " : ", ") : "") + std::string(n);
            ++index;
        }
        if (found < 0) fail(name(key) + " must be " + list);
        value = found;
    }
    return value;
}

const nlohmann::json& JsonReader::required(const char* key, const std::string& what) {
    const nlohmann::json* v = find(key);
    if (!v) fail(name(key) + " is required (" + what + ")");
    return *v;
}

JsonReader JsonReader::child(const char* key) {
    seen_.insert(key);
    static const nlohmann::json empty = nlohmann::json::object();
    auto it = json_.find(key);
    return JsonReader(it != json_.end() ? *it : empty, source_, childPath(key));
}

std::vector<JsonReader> JsonReader::objects(const char* key) {
    std::vector<JsonReader> out;
    const nlohmann::json* v = find(key);
    if (!v) return out;
    if (!v->is_array()) fail(name(key) + " must be an array");
    for (size_t i = 0; i < v->size(); ++i)
        out.emplace_back((*v)[i], source_, childPath(key) + "[" + std::to_string(i) + "]");
    return out;
}

const nlohmann::json* JsonReader::raw(const char* key) {
    return find(key);
}

void JsonReader::finish() const {
    for (auto it = json_.begin(); it != json_.end(); ++it)
        if (!seen_.count(it.key())) fail("unknown key " + name(it.key()));
}

std::string JsonReader::name(const std::string& key) const {
    return "'" + childPath(key) + "'";
}

void JsonReader::fail(const std::string& message) const {
    throw Error(source_ + ": " + message);
}

const nlohmann::json* JsonReader::find(const char* key) {
    seen_.insert(key);
    auto it = json_.find(key);
    return it == json_.end() ? nullptr : &*it;
}

std::string formatNumber(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
}

} // namespace sward
