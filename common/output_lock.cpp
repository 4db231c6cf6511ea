#include "common/output_lock.h"

#include "common/atomic_file.h"
#include "common/error.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace sward {

namespace {

// Every holder writes its pid in the same 11 bytes (padded), so shards writing at once leave one whole pid.
constexpr size_t kPidBytes = 11;

bool alive(long pid) {
    return pid > 0 && (::kill(pid_t(pid), 0) == 0 || errno == EPERM);
}

long pidInFile(int fd) {
    char text[kPidBytes + 1] = {};
    const ssize_t n = ::pread(fd, text, kPidBytes, 0);
    return n > 0 ? std::strtol(text, nullptr, 10) : 0;
}

// The pid of the process holding the lock: a holder writes it just after taking the lock, so a file still empty
// (or naming a dead process) is read again for a moment. 0 when none shows up.
long holderPid(int fd) {
    for (int attempt = 0; attempt < 50; ++attempt) {
        const long pid = pidInFile(fd);
        if (alive(pid)) return pid;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return 0;
}

// The lock file `fd` still bears its name in the folder (a holder's clean exit removes it; a lock on a removed
// file excludes no one).
bool stillNamed(int dirFd, int fd) {
    struct stat held, named;
    return ::fstat(fd, &held) == 0 && ::fstatat(dirFd, kOutputLockFile, &named, AT_SYMLINK_NOFOLLOW) == 0 &&
           held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

std::string heldBy(const std::string& dir, long pid) {
    return "'" + dir + "' is being written by another sward process (" +
           (pid > 0 ? "pid " + std::to_string(pid) : std::string("pid unknown")) +
           "): one writer per folder; wait for it to finish or choose another output folder";
}

int flockMode(OutputLock::Mode mode) {
    return (mode == OutputLock::Mode::Exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
}

} // namespace

void OutputLock::requireFree(const std::string& dir, Mode mode) {
    const std::string path = dir + "/" + kOutputLockFile;
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return; // no lock file (or none usable: the constructor reports that)
    struct stat info;
    const bool held =
        ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && ::flock(fd, flockMode(mode)) != 0 && errno == EWOULDBLOCK;
    const long pid = held ? holderPid(fd) : 0;
    ::close(fd); // releases the probe's lock
    if (held) throw Error(heldBy(dir, pid));
}

OutputLock::OutputLock(const std::string& dir, Mode mode) {
    const std::string path = dir + "/" + kOutputLockFile;
    dirFd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd_ < 0) throw Error("cannot lock output folder '" + dir + "': " + ioErrorReason(errno));
    auto fail = [&](const std::string& message) {
        if (fd_ >= 0) ::close(fd_);
        ::close(dirFd_);
        throw Error(message);
    };
    for (int attempt = 0;; ++attempt) {
        fd_ = ::openat(dirFd_, kOutputLockFile, O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
        if (fd_ < 0) {
            const int error = errno;
            fail("cannot create lock file '" + path + "': " +
                 (error == ELOOP ? std::string("it is a symbolic link (sward never writes through links in an output "
                                               "folder)")
                                 : ioErrorReason(error)));
        }
        struct stat info;
        if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode))
            fail("cannot use lock file '" + path + "': not a regular file");
        if (::flock(fd_, flockMode(mode)) != 0) {
            const int error = errno;
            if (error != EWOULDBLOCK) fail("cannot lock '" + path + "': " + ioErrorReason(error));
            fail(heldBy(dir, holderPid(fd_)));
        }
        if (stillNamed(dirFd_, fd_)) break;
        ::close(fd_);
        fd_ = -1;
        if (attempt == 100) fail("cannot lock '" + path + "': its lock file keeps being replaced");
    }
    std::string pid = std::to_string(long(::getpid()));
    pid.resize(kPidBytes - 1, ' ');
    pid += '\n';
    if (mode == Mode::Exclusive) (void)::ftruncate(fd_, 0);
    if (::pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        fail("cannot write '" + path + "': " + ioErrorReason(errno));
}

OutputLock::~OutputLock() {
    // The last holder removes the file: only then does an exclusive lock succeed (a shard that finishes first
    // leaves it to the others). A failed conversion drops the shared lock, which is being released anyway.
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0 && stillNamed(dirFd_, fd_)) ::unlinkat(dirFd_, kOutputLockFile, 0);
    ::close(fd_);
    ::close(dirFd_);
}

} // namespace sward
