// The one way sward puts a file on disk: encode into memory, then write the bytes atomically, so a file under
// its final name is always complete. A dataset re-run treats every file that exists as complete, and a process
// killed at any instant (SIGKILL, power aside: nothing is fsync'ed) leaves either the old file or the new one.
//
// How: a new file is written as an unnamed O_TMPFILE and linked under its name only when complete (nothing is
// ever visible before, and a killed process leaves nothing behind). A file that replaces another, or a folder
// whose file system lacks O_TMPFILE, goes through a sward-owned temporary ".<name>.sward-<pid>.tmp" in the same
// folder that is renamed over the name; removeStaleTemporaries() deletes those of dead processes, never any
// other "*.tmp". Every write() and close() is checked: a full disk, a quota, an I/O error or a size limit give
// one error "cannot write '<path>': no space left on device" (etc.) and leave no file under <path>. Each step works
// relative to a handle on the file's folder (openat, linkat, renameat), and a link of the file's name is replaced,
// never written through; below an OutputRoot no link on the way is followed either.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace sward {

// Writes `size` bytes as the whole content of `path` (creating or replacing it); throws sward::Error naming
// `path` and the reason on failure, leaving the previous file (if any) untouched.
void writeBytesAtomically(const std::string& path, const void* data, size_t size);
inline void writeTextAtomically(const std::string& path, std::string_view text) {
    writeBytesAtomically(path, text.data(), text.size());
}

// A folder below which writeBytesAtomically and createFileExclusively follow no link: while an OutputRoot lives,
// a path that starts with `dir` (as given, e.g. the dataset's --out) is written relative to a handle on `dir` taken
// here, opening each folder below it with O_NOFOLLOW. A link swapped in for a dataset's folder while a render runs
// is refused ("a folder on its way is a symbolic link ..."), never written through; `dir` itself may be a link the
// user chose. Roots may nest and overlap in time (the longest match wins); thread-safe.
class OutputRoot {
public:
    // Throws "cannot open output folder '<dir>': <reason>" when `dir` is not an existing folder.
    explicit OutputRoot(const std::string& dir);
    OutputRoot(const OutputRoot&) = delete;
    OutputRoot& operator=(const OutputRoot&) = delete;
    ~OutputRoot();

private:
    std::string dir_;
    int fd_ = -1;
};

// Creates `path` with `bytes` only if no file of that name exists, atomically (two processes racing for one
// name: exactly one creates it, complete). Returns false, writing nothing, when `path` already exists.
bool createFileExclusively(const std::string& path, std::string_view bytes);

// The temporary name writeBytesAtomically uses for `path` in process `pid`: "<dir>/.<name>.sward-<pid>.tmp".
std::string temporaryPathFor(const std::string& path, long pid);
// Whether a file name (no folder) is one of sward's temporaries; sets `pid` to the process that made it.
bool isSwardTemporary(std::string_view fileName, long& pid);
// Removes the sward temporaries in `dir` (not recursive) whose process is gone; a live process's temporary
// (a concurrent shard writing into the same folder) and every other file are left alone.
void removeStaleTemporaries(const std::string& dir);

// The reason for an errno value as sward's errors word it ("no space left on device"), lower case.
std::string ioErrorReason(int errorNumber);

} // namespace sward
