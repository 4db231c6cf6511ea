#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace sward::fuzz {

namespace {

std::filesystem::path folder;

void removeFolder() {
    std::error_code ignored; // at exit: nothing left to report to
    std::filesystem::remove_all(folder, ignored);
}

} // namespace

std::string inputFile(const uint8_t* data, size_t size, const std::string& name) {
    if (folder.empty()) {
        // Per process: libFuzzer's -jobs / -fork workers and two targets run side by side must not share files.
        folder = std::filesystem::temp_directory_path() / ("sward-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(folder);
        std::atexit(removeFolder);
    }
    const std::filesystem::path path = folder / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    if (!out.flush()) std::abort(); // a harness failure, not a finding in the parser: stop loudly
    return path.string();
}

} // namespace sward::fuzz
