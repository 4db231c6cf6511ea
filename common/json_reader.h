// The one JSON reader of sward's input files (scenes, vegetation parameters, objects, atlases, ...).
//
// A JsonReader reads typed, range-checked values from one JSON object and rejects keys nobody asked for, so a
// typo never silently falls back to a default. Every error is one sward::Error in one wording:
//   "<source>: '<path>.<key>' must be between 0 and 1 (got 3)"
// where <source> names the file and <path> is the JSON path of the object ("objects[2].path").
#pragma once

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace sward {

// Limits of every JSON input (scene, atlas description): far above any real file, low enough that a hostile
// one can neither exhaust memory nor recurse deep in a consumer that walks the tree.
inline constexpr uint64_t kMaxJsonFileBytes = uint64_t(64) << 20;
inline constexpr uint32_t kMaxJsonDepth = 64;

// The one way sward reads a JSON file: `what` names the kind of file ("scene file"). Throws one sward::Error
// naming the file for a missing / unreadable file ("<path>: cannot open the <what>"), a file over
// kMaxJsonFileBytes, invalid JSON ("<path>: the <what> is not valid JSON (line L, column C)"), nesting deeper than
// kMaxJsonDepth and a key that appears twice in one object ("<path>: 'wind.strength' appears twice").
nlohmann::json readJsonFile(const std::string& path, const std::string& what);
// The same checks for JSON text; `source` names it in errors (the file the text came from).
nlohmann::json parseJsonText(std::string_view text, const std::string& source, const std::string& what);

class JsonReader {
public:
    // `json` must be an object (else the error names `path`, or the whole file when `path` is empty).
    // The reader keeps a reference: `json` must outlive it.
    JsonReader(const nlohmann::json& json, std::string source, std::string path = "");

    // Each getter returns `value` when the key is absent and checks type and range when it is present.
    double number(const char* key, double value, double lo, double hi);
    // A number stored as a float: [lo, hi] must lie within the float range (so the result is finite).
    float numberF(const char* key, float value, float lo, float hi);
    // Exact integers (never rounded through a double, never wrapped): anything else, a fraction, a negative number
    // or one outside [lo, hi] gets "'<key>' must be an integer in [lo, hi] (got <value as written>)".
    uint64_t integer(const char* key, uint64_t value, uint64_t lo, uint64_t hi);
    std::string string(const char* key, std::string value);
    // An array of at most maxCount strings; empty when absent.
    std::vector<std::string> strings(const char* key, size_t maxCount);
    bool boolean(const char* key, bool value);
    template <int N> glm::vec<N, double> vector(const char* key, glm::vec<N, double> value, double lo, double hi);
    // Whole numbers (written as integers or as numbers like 640.0) in [lo, hi].
    template <int N> glm::vec<N, uint32_t> wholeVector(const char* key, glm::vec<N, uint32_t> value, uint32_t lo,
                                                       uint32_t hi);
    // An array of N-number arrays (e.g. points [[x, y], ...]); empty when absent.
    template <int N> std::vector<glm::vec<N, double>> vectors(const char* key, double lo, double hi);
    // The index in `names` of the string under `key`, or `value` when absent: "'<k>' must be a, b or c".
    int choice(const char* key, int value, std::initializer_list<const char*> names);

    bool has(const char* key) const { return json_.contains(key); }
    // Throws "'<path>.<key>' is required (<what>)" when the key is absent; returns its raw value (marked as read).
    const nlohmann::json& required(const char* key, const std::string& what);
    // The object under `key` (an empty object when absent); its errors name "<path>.<key>".
    JsonReader child(const char* key);
    // The elements of the array under `key` (none when absent), each an object read by its own reader whose
    // errors name "<path>.<key>[i]". Throws when the value is not an array or an element is not an object.
    std::vector<JsonReader> objects(const char* key);
    // The raw value under `key` (marked as read), or nullptr when absent: for values with a shape of their own.
    const nlohmann::json* raw(const char* key);
    // Call after reading: any key not read is a typo or an unsupported option.
    void finish() const;

    // "'<path>.<key>'", as the messages write it.
    std::string name(const std::string& key) const;
    // "<path>.<key>": the JSON path of a value under this object, for a parser of its own (e.g. parsePath).
    std::string childPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    const std::string& source() const { return source_; }
    const std::string& path() const { return path_; }
    // Throws sward::Error("<source>: <message>").
    [[noreturn]] void fail(const std::string& message) const;

private:
    const nlohmann::json* find(const char* key);

    const nlohmann::json& json_;
    std::string source_, path_;
    std::set<std::string> seen_;
};

// "%g" of a number, as the range messages print bounds.
std::string formatNumber(double value);

template <int N>
glm::vec<N, double> JsonReader::vector(const char* key, glm::vec<N, double> value, double lo, double hi) {
    if (const nlohmann::json* v = find(key)) {
        if (!v->is_array() || v->size() != N) fail(name(key) + " must be an array of " + std::to_string(N) + " numbers");
        for (int i = 0; i < N; ++i) {
            const nlohmann::json& e = (*v)[size_t(i)];
            if (!e.is_number() || !(e.get<double>() >= lo && e.get<double>() <= hi))
                fail(name(key) + " must hold numbers between " + formatNumber(lo) + " and " + formatNumber(hi));
            value[i] = e.get<double>();
        }
    }
    return value;
}

template <int N>
glm::vec<N, uint32_t> JsonReader::wholeVector(const char* key, glm::vec<N, uint32_t> value, uint32_t lo, uint32_t hi) {
    const glm::vec<N, double> v = vector<N>(key, glm::vec<N, double>(value), lo, hi);
    if (v != glm::floor(v)) fail(name(key) + " must hold whole numbers");
    return glm::vec<N, uint32_t>(v);
}

template <int N> std::vector<glm::vec<N, double>> JsonReader::vectors(const char* key, double lo, double hi) {
    std::vector<glm::vec<N, double>> out;
    const nlohmann::json* v = find(key);
    if (!v) return out;
    const std::string shape = "must be an array of arrays of " + std::to_string(N) + " numbers between " +
                              formatNumber(lo) + " and " + formatNumber(hi);
    if (!v->is_array()) fail(name(key) + " " + shape);
    for (const nlohmann::json& item : *v) {
        if (!item.is_array() || item.size() != N) fail(name(key) + " " + shape);
        glm::vec<N, double>& p = out.emplace_back();
        for (int i = 0; i < N; ++i) {
            const nlohmann::json& e = item[size_t(i)];
            if (!e.is_number() || !(e.get<double>() >= lo && e.get<double>() <= hi)) fail(name(key) + " " + shape);
            p[i] = e.get<double>();
        }
    }
    return out;
}

} // namespace sward
