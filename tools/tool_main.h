// The one way a sward tool runs: parse the command line, run, and turn every failure into one line on stderr
// ("<tool>: error: <message>") and an exit code: 2 for a bad command line, 1 for bad input or a failed run.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <functional>

namespace sward {

inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// Parses `argv` into `app` (--help prints and exits 0), then calls `run`, whose return value is the exit code.
inline int runTool(CLI::App& app, int argc, char** argv, const char* tool, const std::function<int()>& run) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
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
