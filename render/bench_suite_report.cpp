// suite.md (render/bench_suite.h): the suite's JSON as the Markdown table docs/benchmarks.md's "Real GPU" section
// takes in as it is.
#include "render/bench_suite.h"

#include <cmath>
#include <cstdio>

namespace sward {

namespace {

// Numbers with four significant digits (fractions of 1 with six, so 0.999 and 1 stay apart), integers whole.
std::string numberText(const nlohmann::json& value) {
    if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
    if (!value.is_number()) return value.is_string() ? value.get<std::string>() : value.dump();
    const double v = value.get<double>();
    char text[64];
    if (value.is_number_integer() || value.is_number_unsigned() || (std::fabs(v) >= 1e4 && v == std::floor(v)))
        std::snprintf(text, sizeof text, "%.0f", v);
    else if (v > 0.9 && v <= 1.0)
        std::snprintf(text, sizeof text, "%.6g", v);
    else
        std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

std::string listText(const nlohmann::json& object, const char* separator) {
    std::string out;
    for (const auto& [key, value] : object.items())
        out += (out.empty() ? "" : ", ") + key + separator + (value.is_array() ? value.dump() : numberText(value));
    return out;
}

std::string deviceLines(const nlohmann::json& d) {
    const nlohmann::json& limits = d.at("limits");
    std::string heaps;
    for (const nlohmann::json& heap : d.at("memory_heaps")) {
        char text[64];
        std::snprintf(text, sizeof text, "%s%.1f GiB%s", heaps.empty() ? "" : ", ",
                      heap.at("bytes").get<double>() / 1073741824.0,
                      heap.at("device_local").get<bool>() ? " device-local" : "");
        heaps += text;
    }
    return "| device | " + d.at("name").get<std::string>() + " (" + d.at("type").get<std::string>() + ") |\n" +
           "| driver | " + d.at("driver").get<std::string>() + ", Vulkan " + d.at("vulkan_version").get<std::string>() +
           " |\n" + "| UUID | " + d.at("uuid").get<std::string>() + " |\n" + "| limits | max image " +
           numberText(limits.at("max_image_dimension_2d")) + ", samples " + limits.at("sample_counts").dump() +
           ", subgroup " + numberText(limits.at("subgroup_size")) + ", timestamp period " +
           numberText(limits.at("timestamp_period_ns")) + " ns |\n" + "| memory heaps | " + heaps + " |\n";
}

} // namespace

std::string suiteTable(const nlohmann::json& suite) {
    std::string out = "### sward-bench suite (" + suite.at("mode").get<std::string>() + "), " +
                      suite.at("date_utc").get<std::string>() + ", revision " +
                      suite.at("sward_revision").get<std::string>() + "\n\n";
    out += "| | |\n|---|---|\n" + deviceLines(suite.at("device"));
    out += "| host | " + numberText(suite.at("host").at("cpu_threads")) + " CPU threads |\n";
    out += "| whole suite | " + numberText(suite.at("seconds")) + " s, " +
           (suite.at("passed").get<bool>() ? "passed" : "NOT passed") + " |\n\n";
    out += "| figure | parameters | result | s |\n|---|---|---|---|\n";
    for (const std::string& name : suiteFigureNames()) { // in run order (JSON objects are sorted by key)
        if (!suite.at("figures").contains(name)) continue;
        const nlohmann::json& figure = suite.at("figures").at(name);
        const std::string status = figure.at("status");
        const std::string result = status == "measured" ? listText(figure.at("summary"), " ")
                                                        : status + ": " + figure.at("reason").get<std::string>();
        out += "| " + name + " | " + listText(figure.at("parameters"), "=") + " | " + result + " | " +
               (figure.contains("seconds") ? numberText(figure.at("seconds")) : "") + " |\n";
    }
    return out;
}

} // namespace sward
