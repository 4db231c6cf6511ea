#include "common/json_reader.h"

#include "common/error.h"
#include "common/input_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sward {

namespace {

// Builds the document from the parser's events and refuses what the DOM parser would accept silently: a key
// that appears twice in one object (the DOM keeps the last value; a scene that says "strength" twice is a
// mistake, and which value wins must not be an accident of the library) and nesting deeper than kMaxJsonDepth.
//
// Why not nlohmann's parser callback: its DOM builder, after every object that ends inside an array, scans the
// whole array for a discarded element, so an array of n objects costs O(n^2) (200,000 colliders took 20.7 s).
// Here every event is O(1) apart from the key's lookup in its own object (O(log keys)), and the JSON path an
// error names is built only when an error is thrown.
class CheckedDomBuilder : public nlohmann::json_sax<nlohmann::json> {
public:
    explicit CheckedDomBuilder(const std::string& source) : source_(source) {}

    nlohmann::json take() { return std::move(root_); }

    bool null() override { return add(nullptr) != nullptr; }
    bool boolean(bool v) override { return add(v) != nullptr; }
    bool number_integer(number_integer_t v) override { return add(v) != nullptr; }
    bool number_unsigned(number_unsigned_t v) override { return add(v) != nullptr; }
    bool number_float(number_float_t v, const string_t&) override { return add(v) != nullptr; }
    bool string(string_t& v) override { return add(std::move(v)) != nullptr; }
    bool binary(binary_t& v) override { return add(nlohmann::json::binary(std::move(v))) != nullptr; }

    bool start_object(std::size_t) override { return open(nlohmann::json::object()); }
    bool start_array(std::size_t) override { return open(nlohmann::json::array()); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        Frame& top = frames_.back();
        if (top.value->contains(k)) throw Error(source_ + ": '" + join(path(frames_.size()), k) + "' appears twice");
        top.slot = &(*top.value)[k];
        top.key = std::move(k);
        return true;
    }

    // Rethrown as the library's own type, so that the caller tells a syntax error from a number beyond a double.
    bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception& e) override {
        if (const auto* syntax = dynamic_cast<const nlohmann::json::parse_error*>(&e)) throw *syntax;
        if (const auto* range = dynamic_cast<const nlohmann::json::out_of_range*>(&e)) throw *range;
        throw Error(source_ + ": " + e.what());
    }

    // The path of the value being read when the parser stopped (a number too large for a double, say).
    std::string pendingPath() const {
        if (frames_.empty()) return "";
        const Frame& top = frames_.back();
        const std::string base = path(frames_.size());
        return top.value->is_array() ? base + "[" + std::to_string(top.value->size()) + "]" : join(base, top.key);
    }

private:
    struct Frame {
        nlohmann::json* value; // the open array or object
        nlohmann::json* slot;  // in an object: where the value of the last key goes
        std::string key;       // in an object: the last key
    };

    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }
    // The JSON path of the container frames_[count - 1] (the root's is ""): walked only for an error message.
    std::string path(size_t count) const {
        std::string out;
        for (size_t i = 1; i < count; ++i) {
            const Frame& parent = frames_[i - 1];
            out = parent.value->is_array() ? out + "[" + std::to_string(parent.value->size() - 1) + "]"
                                           : join(out, parent.key);
        }
        return out;
    }

    // Stores a value where the parser stands; returns where it lies (stable until its container grows, which
    // cannot happen while it is the open container).
    nlohmann::json* add(nlohmann::json value) {
        if (frames_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        Frame& top = frames_.back();
        if (top.value->is_array()) return &top.value->emplace_back(std::move(value));
        *top.slot = std::move(value);
        return top.slot;
    }
    bool open(nlohmann::json container) {
        if (frames_.size() >= kMaxJsonDepth)
            throw Error(source_ + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        frames_.push_back({add(std::move(container)), nullptr, {}});
        return true;
    }
    bool close() {
        frames_.pop_back();
        return true;
    }

    const std::string& source_;
    nlohmann::json root_;
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
    CheckedDomBuilder check(source);
    try {
        nlohmann::json::sax_parse(text.begin(), text.end(), &check);
        return check.take();
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
    // The input door: a FIFO scene file is refused instead of blocking; the size is checked before reading.
    return parseJsonText(readInputFile(path, what, kMaxJsonFileBytes), path, what);
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
