// Atomic file writing: every file sward writes goes to "<path>.tmp" first and is renamed over <path> only when
// complete, so an interrupted run never leaves a half-written file under a final name (a dataset re-run treats
// any file that exists as complete).
#pragma once

#include "common/error.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace sward {

// Runs `write(tmpPath)`, then renames the temporary file over `path`; on any failure removes the temporary
// file and throws sward::Error naming `path`.
template <typename Write> void writeFileAtomically(const std::string& path, Write&& write) {
    const std::string tmp = path + ".tmp";
    try {
        write(tmp);
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        const std::string what = e.what();
        throw Error(what.rfind("cannot write '" + path + "'", 0) == 0 ? what : "cannot write '" + path + "': " + what);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw Error("cannot write '" + path + "': " + ec.message());
    }
}

inline void writeBytesAtomically(const std::string& path, const void* data, size_t size) {
    writeFileAtomically(path, [&](const std::string& tmp) {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        require(bool(file), "cannot create '" + tmp + "'");
        file.write(static_cast<const char*>(data), std::streamsize(size));
        file.close();
        require(!file.fail(), "write failed (disk full?)");
    });
}

inline void writeTextAtomically(const std::string& path, std::string_view text) {
    writeBytesAtomically(path, text.data(), text.size());
}

} // namespace sward
