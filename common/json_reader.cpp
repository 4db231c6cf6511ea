#include "common/json_reader.h"

#include "common/error.h"

#include <cmath>
#include <cstdio>

namespace sward {

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

uint64_t JsonReader::integer(const char* key, uint64_t value, uint64_t lo, uint64_t hi) {
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_number_integer() || (!v->is_number_unsigned() && v->get<int64_t>() < 0))
            fail(name(key) + " must be a non-negative integer");
        value = v->get<uint64_t>();
        if (value < lo || value > hi)
            fail(name(key) + " must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " +
                 std::to_string(value) + ")");
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
