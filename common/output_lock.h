// One writer per output folder: an advisory flock(2) on "<folder>/.sward.lock", held by sward-render (the dataset
// folder), sward-export (--out) and sward-eval (the report folder) for as long as they write there. A second writer
// fails at once with one line naming the holder's pid (the lock file holds it) instead of mixing its files with the
// first one's. The kernel releases the lock when its process dies, so a stale lock file of a killed run is simply
// taken over; the last holder removes the file on a clean exit, so a finished folder holds no trace of it.
//
// Shared holders: the shards of one `sward-render --shard I/N` run write one folder together, so each takes the lock
// shared; every other writer (a plain render, --overwrite, export, eval) takes it exclusive. The lock file is opened
// relative to the folder's handle with O_NOFOLLOW: a symbolic link of that name is refused, never followed.
#pragma once

#include <string>
#include <string_view>

namespace sward {

inline constexpr const char* kOutputLockFile = ".sward.lock";

class OutputLock {
public:
    enum class Mode { Exclusive, Shared };
    // Locks the existing folder `dir` for writing. Throws "'<dir>' is being written by another sward process
    // (pid N); ..." when a holder's mode excludes `mode`, or a clear error naming the lock file when it cannot be
    // made (a link, a folder, no permission).
    OutputLock(const std::string& dir, Mode mode);
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;
    // Releases the lock; removes the lock file when no other process holds it.
    ~OutputLock();

    // Throws the error the constructor would when another writer holds `dir` against `mode`, writing nothing (no
    // lock file is made): a writer's checks of the folder's content say first that someone else is writing it.
    static void requireFree(const std::string& dir, Mode mode);

private:
    int dirFd_ = -1, fd_ = -1;
};

// Whether a file name (no folder) is the lock file: dataset readers, --overwrite and manifests pass over it.
inline bool isOutputLockFile(std::string_view name) {
    return name == kOutputLockFile;
}

} // namespace sward
