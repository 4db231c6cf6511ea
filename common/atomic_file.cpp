#include "common/atomic_file.h"

#include "common/error.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>
#include <vector>

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

// Where a file goes: its folder, open, and its name in it. Every step of a write is relative to the folder's
// handle (openat, linkat, renameat), so the folder cannot change under the write.
struct Target {
    FileDescriptor folder;
    std::string name;
};

// Removes a named temporary unless it was renamed away.
struct TemporaryName {
    int folder = -1;
    std::string name;
    ~TemporaryName() {
        if (!name.empty()) ::unlinkat(folder, name.c_str(), 0);
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

std::string nameOf(const std::string& path) {
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The registered output roots (OutputRoot): the folder as its owner names it, and a handle on it.
struct RootRegistry {
    std::mutex mutex;
    std::vector<std::pair<std::string, int>> roots;
};
RootRegistry& registry() {
    static RootRegistry instance;
    return instance;
}

// A handle on the root `path` lies below (the longest match), duplicated for the caller; -1 when none. `relative`
// gets the rest of the path.
int rootHandleFor(const std::string& path, std::string& relative) {
    RootRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    const std::pair<std::string, int>* best = nullptr;
    for (const auto& root : r.roots)
        if (path.size() > root.first.size() + 1 && path.starts_with(root.first) && path[root.first.size()] == '/' &&
            (!best || root.first.size() > best->first.size()))
            best = &root;
    if (!best) return -1;
    relative = path.substr(best->first.size() + 1);
    return ::fcntl(best->second, F_DUPFD_CLOEXEC, 0);
}

// Opens the folders of `relative` one by one below the root handle `root` (which it takes over), refusing a link
// (O_NOFOLLOW: ELOOP) or a `..`; 0 or errno.
int openBelowRoot(int root, const std::string& relative, Target& target) {
    target.folder.fd = root;
    size_t begin = 0;
    for (size_t slash; (slash = relative.find('/', begin)) != std::string::npos; begin = slash + 1) {
        const std::string part = relative.substr(begin, slash - begin);
        if (part.empty() || part == ".") continue;
        if (part == "..") return EINVAL;
        const int next = ::openat(target.folder.fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (next < 0) return errno;
        ::close(target.folder.fd);
        target.folder.fd = next;
    }
    target.name = relative.substr(begin);
    return 0;
}

// The folder and name of `path`: below an output root, opened without following a link (a link swapped in for a
// dataset's folder mid-run is refused, never written through); elsewhere the folder as the path names it.
void openTarget(const std::string& path, Target& target) {
    std::string relative;
    if (const int root = rootHandleFor(path, relative); root >= 0) {
        const int error = openBelowRoot(root, relative, target);
        if (error == ELOOP || error == ENOTDIR)
            throw Error("cannot write '" + path + "': a folder on its way is a symbolic link or not a folder (sward " +
                        "writes through no link in an output folder)");
        if (error) fail(path, error);
        return;
    }
    // O_PATH: a folder that may be written but not listed is still a handle for the *at calls.
    target.folder.fd = ::open(folderOf(path).c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (target.folder.fd < 0) fail(path, errno);
    target.name = nameOf(path);
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

// An unnamed file in the target's folder (O_TMPFILE), or -1 where the file system lacks it (or anything else
// fails: the named path then reports the real reason).
int openUnnamed(const Target& target) {
    return ::openat(target.folder.fd, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
}

// Gives the unnamed file `fd` the name `name` in `folder`; fails with EEXIST when the name is taken (a link of
// that name included: linkat never follows it). 0 or errno.
int linkUnnamed(int fd, int folder, const std::string& name) {
    const std::string self = "/proc/self/fd/" + std::to_string(fd);
    if (::linkat(AT_FDCWD, self.c_str(), folder, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
    int error = errno;
    if (error == ENOENT && ::access("/proc/self/fd", F_OK) != 0) { // no /proc: needs CAP_DAC_READ_SEARCH
        if (::linkat(fd, "", folder, name.c_str(), AT_EMPTY_PATH) == 0) return 0;
        error = errno;
    }
    return error;
}

bool nameExists(const Target& target) {
    struct stat info;
    return ::fstatat(target.folder.fd, target.name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0;
}

// Writes `bytes` to a fresh named temporary beside the target (which the caller then renames or links).
void writeNamedTemporary(const std::string& path, const Target& target, const void* data, size_t size,
                         TemporaryName& tmp) {
    tmp.folder = target.folder.fd;
    tmp.name = temporaryPathFor(target.name, long(::getpid()));
    FileDescriptor file;
    file.fd = ::openat(tmp.folder, tmp.name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (file.fd < 0) {
        tmp.name.clear();
        fail(path, errno);
    }
    if (int error = writeAll(file.fd, data, size)) fail(path, error);
    if (int error = file.closeChecked()) fail(path, error);
}

} // namespace

std::string ioErrorReason(int errorNumber) {
    switch (errorNumber) {
    case ENOSPC:
        return "no space left on device";
    case EDQUOT:
        return "disk quota exceeded";
    case EIO:
        return "input/output error";
    case EFBIG:
        return "file too large for the file system or the process's file size limit";
    case EROFS:
        return "read-only file system";
    case EACCES:
    case EPERM:
        return "permission denied";
    case ENOENT:
        return "no such file or folder";
    case ENOTDIR:
        return "a parent is not a folder";
    case EISDIR:
        return "a folder of that name exists";
    default:
        break;
    }
    std::string reason = std::strerror(errorNumber);
    if (!reason.empty()) reason[0] = char(std::tolower(static_cast<unsigned char>(reason[0])));
    return reason;
}

void writeBytesAtomically(const std::string& path, const void* data, size_t size) {
    Target target;
    openTarget(path, target);
    const int folder = target.folder.fd;
    FileDescriptor file;
    if (!nameExists(target)) file.fd = openUnnamed(target);
    TemporaryName tmp;
    if (file.fd >= 0) {
        if (int error = writeAll(file.fd, data, size)) fail(path, error);
        const int error = linkUnnamed(file.fd, folder, target.name);
        if (error == 0) {
            if (int closeError = file.closeChecked()) {
                ::unlinkat(folder, target.name.c_str(), 0);
                fail(path, closeError);
            }
            return;
        }
        if (error != EEXIST) fail(path, error);
        // Someone created `path` meanwhile: replace it like any existing file, through a named temporary.
        tmp.folder = folder;
        tmp.name = temporaryPathFor(target.name, long(::getpid()));
        ::unlinkat(folder, tmp.name.c_str(), 0);
        if (int linkError = linkUnnamed(file.fd, folder, tmp.name)) {
            tmp.name.clear();
            fail(path, linkError);
        }
        if (int closeError = file.closeChecked()) fail(path, closeError);
    } else {
        writeNamedTemporary(path, target, data, size, tmp);
    }
    // rename replaces a link of that name itself; it never writes through it.
    if (::renameat(folder, tmp.name.c_str(), folder, target.name.c_str()) != 0) fail(path, errno);
    tmp.name.clear();
}

bool createFileExclusively(const std::string& path, std::string_view bytes) {
    Target target;
    openTarget(path, target);
    const int folder = target.folder.fd;
    FileDescriptor file;
    file.fd = openUnnamed(target);
    if (file.fd >= 0) {
        if (int error = writeAll(file.fd, bytes.data(), bytes.size())) fail(path, error);
        const int error = linkUnnamed(file.fd, folder, target.name);
        if (error == EEXIST) return false;
        if (error != 0) fail(path, error);
        if (int closeError = file.closeChecked()) {
            ::unlinkat(folder, target.name.c_str(), 0);
            fail(path, closeError);
        }
        return true;
    }
    TemporaryName tmp;
    writeNamedTemporary(path, target, bytes.data(), bytes.size(), tmp);
    // link() never replaces: of several processes exactly one succeeds.
    if (::linkat(folder, tmp.name.c_str(), folder, target.name.c_str(), 0) == 0) return true;
    if (errno == EEXIST) return false;
    fail(path, errno);
}

OutputRoot::OutputRoot(const std::string& dir) : dir_(dir) {
    while (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
    // The folder as the user named it (an --out that is a link is the user's choice); below it nothing is followed.
    fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) throw Error("cannot open output folder '" + dir + "': " + ioErrorReason(errno));
    RootRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    r.roots.emplace_back(dir_, fd_);
}

OutputRoot::~OutputRoot() {
    RootRegistry& r = registry();
    {
        std::lock_guard lock(r.mutex);
        auto it = std::find(r.roots.begin(), r.roots.end(), std::pair<std::string, int>(dir_, fd_));
        if (it != r.roots.end()) r.roots.erase(it);
    }
    ::close(fd_);
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
