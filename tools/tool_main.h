// The one way a sward tool runs: parse the command line, run, and turn every failure into one line on stderr
// ("<tool>: error: <message>") and an exit code (the convention of every tool, tools/merge-manifests.py too):
//   0  success; --help (usage on stdout) and --version ("<tool> <version> (<revision>)" on stdout)
//   1  run-time error: bad input file, failed run
//   2  usage error: unknown option, missing or extra argument, an option value out of its range
// Numbers on the command line go through common/parse_number.h (addUnsigned / addInteger / addReal below), never
// through CLI11's own conversions, which wrap "-5" to 2^64-5 for unsigned targets.
#pragma once

#include "common/error.h"
#include "common/parse_number.h"

#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>

#include <cstdio>
#include <exception>
#include <functional>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#ifndef SWARD_VERSION
#define SWARD_VERSION "unknown"
#endif
#ifndef SWARD_REVISION
#define SWARD_REVISION "unknown"
#endif

namespace sward {

inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
// Most worker threads a --threads option takes (0 means every core): more is a typo, not a machine.
inline constexpr uint64_t kMaxThreadsOption = 1024;

namespace detail {

template <class T> struct OptionValue {
    using type = T;
    static constexpr bool optional = false;
};
template <class T> struct OptionValue<std::optional<T>> {
    using type = T;
    static constexpr bool optional = true;
};

// "--out" of "--out,-o": the name errors use.
inline std::string longName(const std::string& names) {
    std::string first = names.substr(0, names.find(','));
    return first.starts_with('-') ? first : "'" + first + "'";
}

// CLI11's own wording of a parse error, reworded where it is unclear to someone who has not read CLI11.
inline std::string usageMessage(const CLI::App& app, const CLI::ParseError& error) {
    // Unknown arguments first: "--bogus" is the real problem even when it also leaves --out missing.
    for (const std::string& extra : app.remaining(true))
        return (extra.starts_with('-') ? "unknown option '" : "unexpected argument '") + extra + "'";
    const std::string message = error.what();
    if (message == "A subcommand is required") return "a command is required";
    static const std::regex repeated(R"(^(\S+): At Most 1 required but received (\d+)$)");
    static const std::regex missing(R"(^(\S+): \d+ required \S+ missing$)");
    static const std::regex tooFew(R"(^(\S+): At least (\d+) required but received \d+$)");
    std::smatch match;
    if (std::regex_match(message, match, repeated))
        return match[1].str() + " given " + match[2].str() + " times, at most once allowed";
    if (std::regex_match(message, match, missing)) return match[1].str() + " needs a value";
    if (std::regex_match(message, match, tooFew)) return match[1].str() + " needs " + match[2].str() + " values";
    return message;
}

} // namespace detail

// An option whose text `parse(text, flag)` converts while parsing (a sward::Error it throws is a usage error);
// the help shows `target`'s default unless it is a std::optional.
template <class Target, class Parse>
CLI::Option* addParsed(CLI::App& app, const std::string& names, Target& target, const std::string& description,
                       const char* typeName, Parse parse) {
    const std::string flag = detail::longName(names);
    CLI::Option* option = app.add_option_function<std::string>(
        names, [&target, flag, parse](const std::string& text) { target = parse(text, flag); }, description);
    option->type_name(typeName);
    if constexpr (requires(std::ostream & out) { out << target; }) {
        std::ostringstream shown;
        shown << target;
        option->default_str(shown.str());
    }
    return option;
}

// A whole-number option in [min, max] (digits only); Target is an unsigned integer or std::optional of one.
template <class Target>
CLI::Option* addUnsigned(CLI::App& app, const std::string& names, Target& target, uint64_t min, uint64_t max,
                         const std::string& description) {
    using Value = typename detail::OptionValue<Target>::type;
    return addParsed(app, names, target, description, "UINT",
                     [min, max](const std::string& text, const std::string& flag) {
                         return Value(parseUnsigned(text, min, max, flag));
                     });
}

// A whole-number option in [min, max] that may be negative; Target is a signed integer or std::optional of one.
template <class Target>
CLI::Option* addInteger(CLI::App& app, const std::string& names, Target& target, int64_t min, int64_t max,
                        const std::string& description) {
    using Value = typename detail::OptionValue<Target>::type;
    return addParsed(app, names, target, description, "INT",
                     [min, max](const std::string& text, const std::string& flag) {
                         return Value(parseInteger(text, min, max, flag));
                     });
}

// A finite real-number option in [min, max]; Target is float, double or std::optional of one.
template <class Target>
CLI::Option* addReal(CLI::App& app, const std::string& names, Target& target, double min, double max,
                     const std::string& description) {
    using Value = typename detail::OptionValue<Target>::type;
    return addParsed(app, names, target, description, "NUMBER",
                     [min, max](const std::string& text, const std::string& flag) {
                         return Value(parseReal(text, min, max, flag));
                     });
}

// An option whose text must pass `check` (e.g. parseResolution) while parsing, so a bad value is a usage error;
// the text itself is kept in `target` for the library that parses it again.
template <class Target>
CLI::Option* addChecked(CLI::App& app, const std::string& names, Target& target, const std::string& description,
                        const char* typeName, const std::function<void(const std::string& text)>& check) {
    return addParsed(app, names, target, description, typeName, [check](const std::string& text, const std::string&) {
        check(text);
        return text;
    });
}

// MSAA samples: 1 or 4, as everywhere in sward.
template <class Target> CLI::Option* addSamples(CLI::App& app, Target& target, const std::string& description) {
    return addParsed(app, "--samples", target, description, "1|4",
                     [](const std::string& text, const std::string& flag) {
                         const uint64_t samples = parseUnsigned(text, 1, 4, flag);
                         require(samples == 1 || samples == 4, flag + " must be 1 or 4, got '" + text + "'");
                         return uint32_t(samples);
                     });
}

// --frames A:B, the half-open range of frame numbers A .. B-1 every dataset tool takes.
inline CLI::Option* addFrameRange(CLI::App& app, std::optional<std::pair<uint32_t, uint32_t>>& target,
                                  const std::string& description) {
    return addParsed(app, "--frames", target, description, "A:B", [](const std::string& text, const std::string& flag) {
        const auto [first, end] = parseHalfOpenRange(text, 0, kFrameLimit, flag);
        return std::pair<uint32_t, uint32_t>(uint32_t(first), uint32_t(end));
    });
}

// A point "X,Y,Z" of finite numbers (metres), e.g. --camera 10,-4.5,2.
inline CLI::Option* addPoint(CLI::App& app, const std::string& names, std::optional<glm::dvec3>& target,
                             const std::string& description) {
    return addParsed(app, names, target, description, "X,Y,Z", [](const std::string& text, const std::string& flag) {
        const std::string what = flag + " '" + text + "'";
        std::vector<std::string> parts(1);
        for (char c : text)
            if (c == ',')
                parts.emplace_back();
            else
                parts.back().push_back(c);
        require(parts.size() == 3, what + ": expected X,Y,Z in metres, e.g. 10,-4.5,2");
        return glm::dvec3(parseReal(parts[0], -1e9, 1e9, what + ": X"), parseReal(parts[1], -1e9, 1e9, what + ": Y"),
                          parseReal(parts[2], -1e9, 1e9, what + ": Z"));
    });
}

// Adds --version, parses `argv` into `app`, then calls `run`, whose return value is the exit code. Usage errors
// (CLI11's, and sward::Error thrown by an option's parser) exit 2, anything `run` throws exits 1.
inline int runTool(CLI::App& app, int argc, char** argv, const char* tool, const std::function<int()>& run) {
    app.set_version_flag("--version", std::string(tool) + " " + SWARD_VERSION + " (" + SWARD_REVISION + ")",
                         "Print the tool's version and source revision and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e); // --help, --version: printed on stdout, exit 0
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: error: %s (see --help)\n", tool, detail::usageMessage(app, e).c_str());
        return kExitUsage;
    } catch (const Error& e) {
        std::fprintf(stderr, "%s: error: %s (see --help)\n", tool, e.what());
        return kExitUsage;
    }
    try {
        return run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", tool, e.what());
        return kExitFailure;
    }
}

} // namespace sward
