#include "common/atomic_file.h"

#include "common/error.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <vector>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sward {

namespace {

// Closes the descriptor on every path out; close() itself is checked by closeChecked where it matters.
struct FileDescriptor {
    int fd = -1;
    FileDescriptor() = default;
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
    // 0, or the errno of a failed close (NFS reports deferred write errors only here).
    int closeChecked() {
        int result = ::close(fd);
        fd = -1;
        return result == 0 ? 0 : errno;
    }
};

// Removes a named temporary unless it was renamed away.
struct TemporaryName {
    std::string path;
    ~TemporaryName() {
        if (!path.empty()) ::unlink(path.c_str());
    }
};

[[noreturn]] void fail(const std::string& path, int errorNumber) {
    throw Error("cannot write '" + path + "': " + ioErrorReason(errorNumber));
}

std::string folderOf(const std::string& path) {
    const size_t slash = path.rfind('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

// 0, or the errno of the failed write(); a short write is retried, so only a real error (ENOSPC, EIO, EFBIG,
// EDQUOT) ends it.
int writeAll(int fd, const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, std::min(size, size_t(1) << 30));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        p += n;
        size -= size_t(n);
    }
    return 0;
}

// An unnamed file in the folder of `path` (O_TMPFILE), or -1 where the file system lacks it (or anything else
// fails: the named path then reports the real reason).
int openUnnamed(const std::string& path) {
    return ::open(folderOf(path).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
}

// Gives the unnamed file `fd` the name `path`; fails with EEXIST when the name is taken. 0 or errno.
int linkUnnamed(int fd, const std::string& path) {
    const std::string self = "/proc/self/fd/" + std::to_string(fd);
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, path.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
    int error = errno;
    if (error == ENOENT && ::access("/proc/self/fd", F_OK) != 0) { // no /proc: needs CAP_DAC_READ_SEARCH
        if (::linkat(fd, "", AT_FDCWD, path.c_str(), AT_EMPTY_PATH) == 0) return 0;
        error = errno;
    }
    return error;
}

bool nameExists(const std::string& path) {
    struct stat info;
    return ::lstat(path.c_str(), &info) == 0;
}

// Writes `bytes` to a fresh named temporary for `path` (which the caller then renames or links); returns it.
void writeNamedTemporary(const std::string& path, const void* data, size_t size, TemporaryName& tmp) {
    tmp.path = temporaryPathFor(path, long(::getpid()));
    FileDescriptor file;
    file.fd = ::open(tmp.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (file.fd < 0) {
        tmp.path.clear();
        fail(path, errno);
    }
    if (int error = writeAll(file.fd, data, size)) fail(path, error);
    if (int error = file.closeChecked()) fail(path, error);
}

} // namespace

std::string ioErrorReason(int errorNumber) {
    switch (errorNumber) {
    case ENOSPC: return "no space left on device";
    case EDQUOT: return "disk quota exceeded";
    case EIO: return "input/output error";
    case EFBIG: return "file too large for the file system or the process's file size limit";
    case EROFS: return "read-only file system";
    case EACCES:
    case EPERM: return "permission denied";
    case ENOENT: return "no such file or folder";
    case ENOTDIR: return "a parent is not a folder";
    case EISDIR: return "a folder of that name exists";
    default: break;
    }
    std::string reason = std::strerror(errorNumber);
    if (!reason.empty()) reason[0] = char(std::tolower(static_cast<unsigned char>(reason[0])));
    return reason;
}

void writeBytesAtomically(const std::string& path, const void* data, size_t size) {
    FileDescriptor file;
    if (!nameExists(path)) file.fd = openUnnamed(path);
    TemporaryName tmp;
    if (file.fd >= 0) {
        if (int error = writeAll(file.fd, data, size)) fail(path, error);
        const int error = linkUnnamed(file.fd, path);
        if (error == 0) {
            if (int closeError = file.closeChecked()) {
                ::unlink(path.c_str());
                fail(path, closeError);
            }
            return;
        }
        if (error != EEXIST) fail(path, error);
        // Someone created `path` meanwhile: replace it like any existing file, through a named temporary.
        tmp.path = temporaryPathFor(path, long(::getpid()));
        ::unlink(tmp.path.c_str());
        if (int linkError = linkUnnamed(file.fd, tmp.path)) {
            tmp.path.clear();
            fail(path, linkError);
        }
        if (int closeError = file.closeChecked()) fail(path, closeError);
    } else {
        writeNamedTemporary(path, data, size, tmp);
    }
    if (::rename(tmp.path.c_str(), path.c_str()) != 0) fail(path, errno);
    tmp.path.clear();
}

bool createFileExclusively(const std::string& path, std::string_view bytes) {
    FileDescriptor file;
    file.fd = openUnnamed(path);
    if (file.fd >= 0) {
        if (int error = writeAll(file.fd, bytes.data(), bytes.size())) fail(path, error);
        const int error = linkUnnamed(file.fd, path);
        if (error == EEXIST) return false;
        if (error != 0) fail(path, error);
        if (int closeError = file.closeChecked()) {
            ::unlink(path.c_str());
            fail(path, closeError);
        }
        return true;
    }
    TemporaryName tmp;
    writeNamedTemporary(path, bytes.data(), bytes.size(), tmp);
    // link() never replaces: of several processes exactly one succeeds.
    if (::link(tmp.path.c_str(), path.c_str()) == 0) return true;
    if (errno == EEXIST) return false;
    fail(path, errno);
}

std::string temporaryPathFor(const std::string& path, long pid) {
    const size_t slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    return folder + "." + name + ".sward-" + std::to_string(pid) + ".tmp";
}

bool isSwardTemporary(std::string_view fileName, long& pid) {
    constexpr std::string_view kSuffix = ".tmp", kMarker = ".sward-";
    if (fileName.size() < 2 || fileName[0] != '.' || !fileName.ends_with(kSuffix)) return false;
    const std::string_view stem = fileName.substr(0, fileName.size() - kSuffix.size());
    const size_t marker = stem.rfind(kMarker);
    if (marker == std::string_view::npos || marker < 2) return false; // "." + at least one character of the name
    const std::string_view digits = stem.substr(marker + kMarker.size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return false;
    pid = std::stol(std::string(digits));
    return pid > 0;
}

void removeStaleTemporaries(const std::string& dir) {
    DIR* folder = ::opendir(dir.c_str());
    if (!folder) return;
    std::vector<std::string> stale;
    while (const dirent* entry = ::readdir(folder)) {
        long pid = 0;
        if (!isSwardTemporary(entry->d_name, pid) || pid == long(::getpid())) continue;
        // A process that still runs (kill succeeds or is merely not permitted) may still rename its temporary.
        if (::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue;
        stale.push_back(dir + "/" + entry->d_name);
    }
    ::closedir(folder);
    for (const std::string& path : stale) ::unlink(path.c_str());
}

} // namespace sward
