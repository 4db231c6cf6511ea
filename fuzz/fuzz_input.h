// Shared by the fuzz mains: hands one fuzz input to a loader that reads a file, and runs a loader expecting only
// sward::Error. Everything else (a crash, a sanitizer report, any other exception) ends the process, which is
// what libFuzzer reports as a finding.
#pragma once

#include "common/error.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace sward::fuzz {

// Writes bytes to `name` in a folder private to this process (under TMPDIR; removed at exit) and returns its path.
// The loaders take paths, so the file is how the input reaches them; the same name is overwritten every run.
std::string inputFile(const uint8_t* data, size_t size, const std::string& name);

// Runs load(); a sward::Error is bad input rejected as it should be. Returns 0 (libFuzzer's "keep going").
template <typename Load> int expectOnlyErrors(Load&& load) {
    try {
        load();
    } catch (const Error&) {
    }
    return 0;
}

} // namespace sward::fuzz
